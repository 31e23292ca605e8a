// Angles: one wrapping rule for the whole core.
#pragma once

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace robokin {

inline constexpr double kPi = M_PI;

// a wrapped to [-pi, pi] (exact: std::remainder by 2 pi, which leaves |a| <= pi as it is: the
// quotient rounds to 0, half to even at +-pi; skipping the call there is the same result, faster).
// For pi < |a| < 3 pi the quotient is +-1 and a -+ 2 pi is exact (Sterbenz: a within [pi, 4 pi]):
// the same result again (its zero signed as a's), without the call. Both cases in one branch-free
// step (m minus 2 pi masked by m > pi, then a multiplication by +-1, all exact): angles of random
// poses, half of them beyond pi, left a branch between them to chance. On x86-64 the mask is
// SSE2's compare: GCC turned both a select and a multiplication by (m > pi) into that branch.
inline double wrap_angle(double a) {
  const double m = std::abs(a);
  if (!(m < 3.0 * M_PI)) return std::remainder(a, 2.0 * M_PI);  // NaN too
#if defined(__SSE2__)
  const __m128d vm = _mm_set_sd(m);
  const __m128d turn = _mm_and_pd(_mm_cmpgt_sd(vm, _mm_set_sd(M_PI)), _mm_set_sd(2.0 * M_PI));
  const double r = _mm_cvtsd_f64(_mm_sub_sd(vm, turn));  // -0 for -2 pi, as remainder
#else
  const double r = m - (m > M_PI ? 2.0 * M_PI : 0.0);
#endif
  return std::copysign(1.0, a) * r;
}

}  // namespace robokin
