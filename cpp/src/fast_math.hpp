// sincos and atan2 to a couple of ulp, branch-free and call-free so that loops over poses
// vectorise: the hot part of the 3-RRR inverse model.
#pragma once

#include <cmath>

namespace robokin {

namespace simd {

// Round to nearest for |x| < 2^51 (the default rounding mode does the work).
inline double round_nearest(double x) {
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  return (x + kMagic) - kMagic;
}

// sin and cos for |a| < 1e5: a = k pi/2 + r, |r| <= pi/4 (pi/2 in two parts, k kHi exact), Taylor
// series of sin r to r^15 and cos r to r^16 (remainders below 5e-17).
inline void sincos(double a, double& s, double& c) {
  constexpr double kHi = 1.5707963267341256;     // pi/2 to 33 bits
  constexpr double kLo = 6.077100506506192e-11;  // pi/2 - kHi
  const double k = round_nearest(a * (2 / M_PI));
  const double r = (a - k * kHi) - k * kLo, r2 = r * r;
  const double sp = 1.0 / 6 + r2 * (-1.0 / 120 + r2 * (1.0 / 5040 + r2 * (-1.0 / 362880 + r2 * (1.0 / 39916800 +
                    r2 * (-1.0 / 6227020800 + r2 * (1.0 / 1307674368000))))));
  const double cp = -0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                    r2 * (1.0 / 479001600 + r2 * (-1.0 / 87178291200 + r2 * (1.0 / 20922789888000)))))));
  const double sr = r - r * r2 * sp, cr = 1 + r2 * cp;
  const double q = k - 4 * round_nearest((k - 1.5) * 0.25);  // k mod 4 in {0, 1, 2, 3}
  const bool odd = (q == 1) | (q == 3);
  const double ss = odd ? cr : sr, cc = odd ? sr : cr;
  s = q >= 2 ? -ss : ss;
  c = ((q == 1) | (q == 2)) ? -cc : cc;
}

// atan2(y, x) for (x, y) != (0, 0): t = min / max of |x|, |y| in [0, 1]; above tan(pi/8) use
// atan t = pi/4 + atan((t - 1) / (t + 1)) (one division either way); then halve the angle,
// atan v = 2 atan(v / (1 + sqrt(1 + v^2))), |w| <= tan(pi/16), and the odd Taylor series to w^23
// leaves less than 2e-19.
inline double atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const bool swap = ay > ax;
  const double num = swap ? ax : ay, den = swap ? ay : ax;
  const bool big = num > 0.41421356237309503 * den;
  const double v = (big ? num - den : num) / (big ? num + den : den);
  const double w = v / (1 + std::sqrt(1 + v * v)), w2 = w * w;
  const double p = -1.0 / 3 + w2 * (1.0 / 5 + w2 * (-1.0 / 7 + w2 * (1.0 / 9 + w2 * (-1.0 / 11 + w2 * (1.0 / 13 +
                   w2 * (-1.0 / 15 + w2 * (1.0 / 17 + w2 * (-1.0 / 19 + w2 * (1.0 / 21 + w2 * (-1.0 / 23))))))))));
  double a = 2 * (w + w * w2 * p) + (big ? M_PI_4 : 0.0);
  a = swap ? M_PI_2 - a : a;
  a = x < 0 ? M_PI - a : a;
  return y < 0 ? -a : a;
}

}  // namespace simd

}  // namespace robokin
