// The AVX2 + FMA build of fast_math.hpp's loops (CMakeLists.txt compiles this file alone with
// -mavx2 -mfma: sleef.h declares its AVX2 routines only then), on SLEEF's deterministic ("finz")
// routines: the bits of fast_math_avx512.cpp's. Called only when the CPU has both (fast_math.cpp
// asks detected_isa(), isa.hpp).
#include <sleef.h>

#include "fast_math_loops.hpp"

namespace robokin {

namespace vmath {

namespace {

struct Avx2 {
  static constexpr int width = 4;
  static void sincos(const double* x, double* s, double* c) {
    const Sleef___m256d_2 r = Sleef_finz_sincosd4_u10avx2(_mm256_loadu_pd(x));
    _mm256_storeu_pd(s, r.x);
    _mm256_storeu_pd(c, r.y);
  }
  static void atan2(const double* y, const double* x, double* out) {
    _mm256_storeu_pd(out, Sleef_finz_atan2d4_u10avx2(_mm256_loadu_pd(y), _mm256_loadu_pd(x)));
  }
};

}  // namespace

void sincos_avx2(const double* x, double* s, double* c, long n) { sincos_loop<Avx2>(x, s, c, n); }

void atan2_avx2(const double* y, const double* x, double* out, long n) { atan2_loop<Avx2>(y, x, out, n); }

}  // namespace vmath

}  // namespace robokin
