// Angles: one wrapping rule for the whole core.
#pragma once

#include <cmath>

namespace robokin {

// a wrapped to [-pi, pi] (exact: std::remainder by 2 pi).
inline double wrap_angle(double a) { return std::remainder(a, 2.0 * M_PI); }

}  // namespace robokin
