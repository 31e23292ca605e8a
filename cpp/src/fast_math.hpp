// atan2 to a few ulp, about twice as fast as libm's and without data-dependent branches (random
// quadrants would mispredict): the hot part of the 3-RRR inverse model.
#pragma once

#include <array>
#include <cmath>

namespace robokin {

// t = num / den = min(|x|, |y|) / max(|x|, |y|) in [0, 1] is split at the nearest c = k / 16, and
// atan t = atan c + atan u with u = (t - c) / (1 + t c), |u| < 1/32, where the odd Taylor series
// of atan u to u^11 leaves less than 1e-19. atan(k / 16) is tabulated with libm.
inline double fast_atan2(double y, double x) {
  static const std::array<double, 17> table = [] {
    std::array<double, 17> t{};
    for (int k = 0; k <= 16; ++k) t[k] = std::atan(k / 16.0);
    return t;
  }();
  const double ax = std::abs(x), ay = std::abs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay, den = swap ? ay : ax;
  if (!(den > 0) || std::isinf(den)) return std::atan2(y, x);  // zeros, inf, NaN: libm's conventions
  // One division for both t = num / den and u = (num - c den) / (den + c num). The first, to
  // pick c, only needs to be close: c is then exact and u is computed from num and den.
  const int k = static_cast<int>(num / den * 16 + 0.5);
  const double c = k * (1.0 / 16);
  const double u = (num - c * den) / (den + c * num), u2 = u * u;
  const double series =
      u * (1 + u2 * (-1.0 / 3 + u2 * (1.0 / 5 + u2 * (-1.0 / 7 + u2 * (1.0 / 9 + u2 * (-1.0 / 11))))));
  double a = table[k] + series;
  a = swap ? M_PI_2 - a : a;
  a = x < 0 ? M_PI - a : a;
  return std::copysign(a, y);
}

}  // namespace robokin
