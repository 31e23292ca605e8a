// The AVX-512F build of fast_math.hpp's loops (CMakeLists.txt compiles this file alone with
// -mavx512f: sleef.h declares its AVX-512 routines only then), on SLEEF's deterministic ("finz")
// routines: the bits of fast_math_avx2.cpp's. Called for arrays of 32 values or more when the CPU
// has it (fast_math.cpp asks detected_isa(), isa.hpp).
#include <sleef.h>

#include "fast_math_loops.hpp"

namespace robokin {

namespace vmath {

namespace {

struct Avx512 {
  static constexpr int width = 8;
  static void sincos(const double* x, double* s, double* c) {
    const Sleef___m512d_2 r = Sleef_finz_sincosd8_u10avx512f(_mm512_loadu_pd(x));
    _mm512_storeu_pd(s, r.x);
    _mm512_storeu_pd(c, r.y);
  }
  static void atan2(const double* y, const double* x, double* out) {
    _mm512_storeu_pd(out, Sleef_finz_atan2d8_u10avx512f(_mm512_loadu_pd(y), _mm512_loadu_pd(x)));
  }
};

}  // namespace

void sincos_avx512(const double* x, double* s, double* c, long n) { sincos_loop<Avx512>(x, s, c, n); }

void atan2_avx512(const double* y, const double* x, double* out, long n) { atan2_loop<Avx512>(y, x, out, n); }

}  // namespace vmath

}  // namespace robokin
