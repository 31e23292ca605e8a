// Angles: one wrapping rule for the whole core.
#pragma once

#include <cmath>

namespace robokin {

// a wrapped to [-pi, pi] (exact: std::remainder by 2 pi, which leaves |a| <= pi as it is: the
// quotient rounds to 0, half to even at +-pi; skipping the call there is the same result, faster).
inline double wrap_angle(double a) { return std::abs(a) <= M_PI ? a : std::remainder(a, 2.0 * M_PI); }

}  // namespace robokin
