// SLEEF behind fast_math.hpp: the SSE2 loops (x86-64's baseline) here, the AVX2 + FMA ones in
// fast_math_avx2.cpp and the AVX-512 ones in fast_math_avx512.cpp (all from fast_math_loops.hpp),
// chosen by detected_isa() (isa.hpp).
#include "fast_math.hpp"

#include "isa.hpp"

#include <cmath>

#if defined(__x86_64__) && defined(__SSE2__)
#include <sleef.h>

#include "fast_math_loops.hpp"
#define ROBOKIN_SLEEF 1
#endif

namespace robokin {

namespace vmath {

#ifdef ROBOKIN_SLEEF
void sincos_avx2(const double* x, double* s, double* c, long n);  // fast_math_avx2.cpp
void atan2_avx2(const double* y, const double* x, double* out, long n);
void sincos_avx512(const double* x, double* s, double* c, long n);  // fast_math_avx512.cpp
void atan2_avx512(const double* y, const double* x, double* out, long n);

namespace {

struct Sse2 {
  static constexpr int width = 2;
  static void sincos(const double* x, double* s, double* c) {
    const Sleef___m128d_2 r = Sleef_sincosd2_u10sse2(_mm_loadu_pd(x));
    _mm_storeu_pd(s, r.x);
    _mm_storeu_pd(c, r.y);
  }
  static void atan2(const double* y, const double* x, double* out) {
    _mm_storeu_pd(out, Sleef_atan2d2_u10sse2(_mm_loadu_pd(y), _mm_loadu_pd(x)));
  }
};

using kernel::detected_isa;
using kernel::Isa;

// Arrays of at least this many values (batch FK's blocks: 32 lanes a joint) go through AVX-512
// where the CPU has it; shorter ones, a single call's few, through AVX2, because AVX-512 for every
// length made the single calls slower (the measurements, and the CPUs they were made on, are in
// benchmarks/README.md).
constexpr long kWide = 32;

}  // namespace

void sincos(const double* x, double* s, double* c, long n) {
  const Isa isa = detected_isa();
  if (isa == Isa::Avx512 && n >= kWide) return sincos_avx512(x, s, c, n);
  if (isa != Isa::Baseline) return sincos_avx2(x, s, c, n);
  sincos_loop<Sse2>(x, s, c, n);
}

void atan2(const double* y, const double* x, double* out, long n) {
  const Isa isa = detected_isa();
  if (isa == Isa::Avx512 && n >= kWide) return atan2_avx512(y, x, out, n);
  if (isa != Isa::Baseline) return atan2_avx2(y, x, out, n);
  atan2_loop<Sse2>(y, x, out, n);
}
#else
// Not x86-64: libm, element by element (the same function for every element as well).
void sincos(const double* x, double* s, double* c, long n) {
  for (long k = 0; k < n; ++k) s[k] = std::sin(x[k]), c[k] = std::cos(x[k]);
}

void atan2(const double* y, const double* x, double* out, long n) {
  for (long k = 0; k < n; ++k) out[k] = std::atan2(y[k], x[k]);
}
#endif

}  // namespace vmath

}  // namespace robokin
