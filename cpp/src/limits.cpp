// The check of a (lower, upper) pair of joint limits (limits.hpp).
#include "robokin/limits.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

void validate_limits(int dof, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  if (lower.size() == 0 && upper.size() == 0) return;
  if (lower.size() != dof || upper.size() != dof)
    throw std::invalid_argument("limits: expected (lower, upper) with " + std::to_string(dof) +
                                " values each, got " + std::to_string(lower.size()) + " and " +
                                std::to_string(upper.size()));
  for (int i = 0; i < dof; ++i) {
    if (std::isnan(lower(i)) || std::isnan(upper(i)))
      throw std::invalid_argument("limits: joint " + std::to_string(i) + " has a NaN limit");
    if (lower(i) > upper(i))
      throw std::invalid_argument("limits: joint " + std::to_string(i) +
                                  " has its lower limit above its upper limit");
    if (lower(i) == INFINITY || upper(i) == -INFINITY)
      throw std::invalid_argument("limits: joint " + std::to_string(i) +
                                  " has no admissible value (lower +inf or upper -inf)");
  }
}

bool fit_limits(double* q, int n, const JointLimits& lim) {
  const bool limited = lim.lower.size() != 0;
  for (int i = 0; i < n; ++i) {
    const bool revolute = lim.prismatic.empty() || !lim.prismatic[i];
    if (!limited) {
      if (revolute) q[i] = wrap_angle(q[i]);
      continue;
    }
    const double lo = lim.lower(i), hi = lim.upper(i);
    if (revolute && lo <= -M_PI && hi >= M_PI) {  // settle_into_limits' first case, always taken
      if (!std::isfinite(q[i])) return false;
      q[i] = wrap_angle(q[i]);
      continue;
    }
    const double tol = 1e-12 * std::max(1.0, std::abs(q[i]));
    if (!settle_into_limits(q[i], lo, hi, revolute, tol)) return false;
  }
  return true;
}

}  // namespace robokin
