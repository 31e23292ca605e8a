// Angles: one wrapping rule for the whole core.
#pragma once

#include <cmath>

namespace robokin {

// a wrapped to [-pi, pi] (exact: std::remainder by 2 pi, which leaves |a| <= pi as it is: the
// quotient rounds to 0, half to even at +-pi; skipping the call there is the same result, faster).
// For pi < |a| < 3 pi the quotient is +-1 and a -+ 2 pi is exact (Sterbenz: a within [pi, 4 pi]):
// the same result again (its zero signed as a's), without the call. Both cases in one branch-free
// step (a select and a multiplication by +-1, both exact): angles of random poses, half of them
// beyond pi, left the branch between them to chance.
inline double wrap_angle(double a) {
  const double m = std::abs(a);
  if (!(m < 3.0 * M_PI)) return std::remainder(a, 2.0 * M_PI);  // NaN too
  const double r = m - (m > M_PI ? 2.0 * M_PI : 0.0);               // -0 for -2 pi, as remainder
  return std::copysign(1.0, a) * r;
}

}  // namespace robokin
