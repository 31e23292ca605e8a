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

void fit_limits_rows(double* q, int rows, int n, const JointLimits& lim, bool* ok, int keep) {
  std::fill(ok, ok + rows, true);
  const bool limited = lim.lower.size() != 0;
  // The common case, every joint revolute and free to turn by a whole turn (limits, if any, that
  // hold [-pi, pi]): each value wrapped (settle_into_limits' first case), in one pass over all rows.
  bool wrap_only = true;
  for (int i = 0; i < n && wrap_only; ++i)
    wrap_only = i == keep || (lim.prismatic.empty() || !lim.prismatic[i]) && (!limited || (lim.lower(i) <= -M_PI && lim.upper(i) >= M_PI));
  if (wrap_only) {
    for (int r = 0; r < rows; ++r)
      for (int i = 0; i < n; ++i) {
        if (i == keep) continue;
        double& v = q[r * n + i];
        if (limited && !std::isfinite(v)) ok[r] = false;
        v = wrap_angle(v);
      }
    return;
  }
  // Otherwise joint by joint, row by row (a wide revolute joint's wrap is settle_into_limits'
  // first case, always taken there).
  for (int i = 0; i < n; ++i) {
    if (i == keep) continue;
    const bool revolute = lim.prismatic.empty() || !lim.prismatic[i];
    if (!limited) {
      if (revolute)
        for (int r = 0; r < rows; ++r) q[r * n + i] = wrap_angle(q[r * n + i]);
      continue;
    }
    const double lo = lim.lower(i), hi = lim.upper(i);
    for (int r = 0; r < rows; ++r) {
      double& v = q[r * n + i];
      const double tol = 1e-12 * std::max(1.0, std::abs(v));
      if (settle_into_limits(v, lo, hi, revolute, tol)) continue;
      ok[r] = false;  // v is unchanged: reported as without limits
      if (revolute) v = wrap_angle(v);
    }
  }
}

bool fit_limits(double* q, int n, const JointLimits& lim, int keep) {
  bool ok;
  fit_limits_rows(q, 1, n, lim, &ok, keep);
  return ok;
}

}  // namespace robokin
