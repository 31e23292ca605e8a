// SLEEF behind fast_math.hpp: the SSE2 loops (x86-64's baseline) here, the AVX2 + FMA ones in
// fast_math_avx2.cpp, the choice made once per process from what the CPU has.
#include "fast_math.hpp"

#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__SSE2__)
#include <sleef.h>
#define ROBOKIN_SLEEF 1
#endif

namespace robokin {

namespace vmath {

#ifdef ROBOKIN_SLEEF
void sincos_avx2(const double* x, double* s, double* c, long n);  // fast_math_avx2.cpp
void atan2_avx2(const double* y, const double* x, double* out, long n);

namespace {

void sincos_sse2(const double* x, double* s, double* c, long n) {
  long k = 0;
  for (; k + 2 <= n; k += 2) {
    const Sleef___m128d_2 r = Sleef_sincosd2_u10sse2(_mm_loadu_pd(x + k));
    _mm_storeu_pd(s + k, r.x);
    _mm_storeu_pd(c + k, r.y);
  }
  if (k < n) {  // the tail through a padded vector: the same routine as every other element
    double in[2] = {x[k], 0.0}, so[2], co[2];
    const Sleef___m128d_2 r = Sleef_sincosd2_u10sse2(_mm_loadu_pd(in));
    _mm_storeu_pd(so, r.x);
    _mm_storeu_pd(co, r.y);
    s[k] = so[0], c[k] = co[0];
  }
}

void atan2_sse2(const double* y, const double* x, double* out, long n) {
  long k = 0;
  for (; k + 2 <= n; k += 2)
    _mm_storeu_pd(out + k, Sleef_atan2d2_u10sse2(_mm_loadu_pd(y + k), _mm_loadu_pd(x + k)));
  if (k < n) {
    double yi[2] = {y[k], 0.0}, xi[2] = {x[k], 1.0}, o[2];
    _mm_storeu_pd(o, Sleef_atan2d2_u10sse2(_mm_loadu_pd(yi), _mm_loadu_pd(xi)));
    out[k] = o[0];
  }
}

bool avx2() {
  static const bool yes = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return yes;
}

}  // namespace

void sincos(const double* x, double* s, double* c, long n) {
  if (avx2()) return sincos_avx2(x, s, c, n);
  sincos_sse2(x, s, c, n);
}

void atan2(const double* y, const double* x, double* out, long n) {
  if (avx2()) return atan2_avx2(y, x, out, n);
  atan2_sse2(y, x, out, n);
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
