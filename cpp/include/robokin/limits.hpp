// Joint limits: one check of a (lower, upper) pair and one rule for bringing a joint value within
// them, shared by Chain, the numerical IK, the closed forms and the RPR batch.
#pragma once

#include "robokin/angles.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace robokin {

// Limits as the closed forms take them: empty lower/upper when there are none.
struct JointLimits {
  Eigen::VectorXd lower, upper;
  std::vector<bool> prismatic;  // empty: every joint revolute
};

// Checks a (lower, upper) pair for dof joints (both empty: no limits): sizes, NaN, lower > upper,
// a lower limit of +inf or an upper of -inf. Throws std::invalid_argument("limits: ...").
void validate_limits(int dof, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

// Brings each joint of a solution q (n joints) within `lim` by settle_into_limits, with a hair of
// tolerance (1e-12 relative) so that a solution at a limit is not lost to rounding; false when a
// joint cannot be brought within its limits (that joint is then left as it is, a revolute one
// wrapped to [-pi, pi]; the others are still brought within theirs). The closed forms' mask.
// Joint `keep` (a held joint, its value within its limits by the caller's check) is left as it is.
bool fit_limits(double* q, int n, const JointLimits& lim, int keep = -1);
// fit_limits on each of `rows` solutions (row-major, n joints each): ok[r] is its result for row r.
void fit_limits_rows(double* q, int rows, int n, const JointLimits& lim, bool* ok, int keep = -1);

// Brings v within [lo, hi], as it is when it is within (to tol, then clamped onto the limit), a
// revolute joint's value otherwise by a multiple of 2 pi: to the nearest value of its class, the
// least above lo when v is below, the greatest below hi when v is above. False (v unchanged) when
// v is not finite or no value fits. This is the rule during an iteration: no jumps within limits.
inline bool fit_into_limits(double& v, double lo, double hi, bool revolute, double tol = 0.0) {
  if (!std::isfinite(v)) return false;
  if (v >= lo - tol && v <= hi + tol) {
    v = std::min(std::max(v, lo), hi);
    return true;
  }
  if (!revolute || !(hi - lo >= 0)) return false;
  constexpr double kTwoPi = 2.0 * M_PI;
  const double w = v < lo ? v + std::ceil((lo - tol - v) / kTwoPi) * kTwoPi
                          : v - std::ceil((v - hi - tol) / kTwoPi) * kTwoPi;
  if (!(std::isfinite(w) && w >= lo - tol && w <= hi + tol)) return false;
  v = std::min(std::max(w, lo), hi);
  return true;
}

// The value a solution is reported with: a revolute angle wrapped to [-pi, pi] when that is within
// the limits, else fit_into_limits. False when nothing fits.
inline bool settle_into_limits(double& v, double lo, double hi, bool revolute, double tol = 0.0) {
  if (revolute && std::isfinite(v)) {
    const double w = wrap_angle(v);
    if (w >= lo - tol && w <= hi + tol) {
      v = std::min(std::max(w, lo), hi);
      return true;
    }
  }
  return fit_into_limits(v, lo, hi, revolute, tol);
}

// The finite point of [lo, hi] nearest to v (NaN counts as 0; an infinite v beyond an infinite
// limit gives the other limit, or 0 when both are infinite).
inline double nearest_in_limits(double v, double lo, double hi) {
  if (std::isnan(v)) v = 0.0;
  v = std::min(std::max(v, lo), hi);
  if (std::isfinite(v)) return v;
  if (v > 0) return std::isfinite(lo) ? lo : std::min(0.0, hi);
  return std::isfinite(hi) ? hi : std::max(0.0, lo);
}

}  // namespace robokin
