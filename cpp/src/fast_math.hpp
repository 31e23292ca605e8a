// sincos and atan2 to a couple of ulp, branch-free and call-free so that loops over poses
// vectorise: the hot part of the 3-RRR inverse model.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace robokin {

namespace simd {

// True where sincos below is accurate (a few ulp); elsewhere (and for NaN) use std::sin / std::cos,
// whose reduction is exact at any size.
inline bool sincos_in_range(double x) { return std::abs(x) <= 1e5; }

// sin and cos of x for |x| <= 1e5. Cody-Waite reduction by pi/2 (pi/2 split in three parts of 33,
// 33 and 53 bits, so q * part is exact for |q| < 2^20), Taylor polynomials of sin and cos on
// |r| <= pi/4 carried to r^17 / r^18 (truncation below 1e-19), the quadrant picked with bit
// operations: no branch and no call, so loops over it vectorise.
inline void sincos(double x, double& s, double& c) {
  constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
  constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer, kept in the low bits
  constexpr double kPio2A = 0x1.921fb54400000p+0, kPio2B = 0x1.0b4611a600000p-34,
                   kPio2C = 0x1.3198a2e037073p-69;
  const double shifted = x * kTwoOverPi + kShift;
  std::uint64_t quadrant;
  std::memcpy(&quadrant, &shifted, sizeof quadrant);
  const double q = shifted - kShift;
  const double r = ((x - q * kPio2A) - q * kPio2B) - q * kPio2C;
  const double r2 = r * r;
  const double sr =
      r + r * r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 + r2 * (-2.505210838544172e-08 +
          r2 * (1.6059043836821613e-10 + r2 * (-7.647163731819816e-13 + r2 * 2.8114572543455206e-15)))))));
  const double cr =
      1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 + r2 * (-2.755731922398589e-07 +
          r2 * (2.08767569878681e-09 + r2 * (-1.1470745597729725e-11 + r2 * (4.779477332387385e-14 +
          r2 * -1.5619206968586225e-16))))))));
  std::uint64_t sb, cb;
  std::memcpy(&sb, &sr, sizeof sb);
  std::memcpy(&cb, &cr, sizeof cb);
  const std::uint64_t swap = std::uint64_t{0} - (quadrant & 1);  // odd quadrant: sin <-> cos
  std::uint64_t so = (cb & swap) | (sb & ~swap), co = (sb & swap) | (cb & ~swap);
  so ^= (quadrant & 2) << 62;        // quadrants 2, 3: sin changes sign
  co ^= ((quadrant + 1) & 2) << 62;  // quadrants 1, 2: cos changes sign
  std::memcpy(&s, &so, sizeof so);
  std::memcpy(&c, &co, sizeof co);
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
