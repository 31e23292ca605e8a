// The planar RPR arm of the RPR study: tip = (L1 + t2) u(t1) + L3 u(t1 + t3), u(a) = (cos a, sin a).
#pragma once

#include "robokin/chain.hpp"

namespace robokin {

// The self-motion set of a tip position p: for each sample of t1, r = L1 + t2 solves
// |p - r u(t1)| = L3, a quadratic in r with two roots (branch 0: the smaller r, branch 1: the
// larger). out has 2 x count x 3 entries (t1, t2, t3); rows with no real root or outside the
// limits [lower, upper] are NaN. t3 is brought into its limits by settle_into_limits (limits.hpp).
void rpr_self_motion(const Eigen::Vector2d& p, const double* t1, long count, double l1, double l3,
                     const Vector& lower, const Vector& upper, double* out);

}  // namespace robokin
