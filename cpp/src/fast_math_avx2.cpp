// The AVX2 + FMA build of fast_math.hpp's loops (CMakeLists.txt compiles this file alone with
// -mavx2 -mfma: sleef.h declares its AVX2 routines only then). Called only when the CPU has both
// (fast_math.cpp checks); nothing here is inline or shared with other files.
#include <sleef.h>

#include <cstring>

namespace robokin {

namespace vmath {

void sincos_avx2(const double* x, double* s, double* c, long n) {
  long k = 0;
  for (; k + 4 <= n; k += 4) {
    const Sleef___m256d_2 r = Sleef_sincosd4_u10avx2(_mm256_loadu_pd(x + k));
    _mm256_storeu_pd(s + k, r.x);
    _mm256_storeu_pd(c + k, r.y);
  }
  if (k < n) {  // the tail through a padded vector: the same routine as every other element
    const size_t m = static_cast<size_t>(n - k);
    double in[4] = {0.0, 0.0, 0.0, 0.0}, so[4], co[4];
    std::memcpy(in, x + k, sizeof(double) * m);
    const Sleef___m256d_2 r = Sleef_sincosd4_u10avx2(_mm256_loadu_pd(in));
    _mm256_storeu_pd(so, r.x);
    _mm256_storeu_pd(co, r.y);
    std::memcpy(s + k, so, sizeof(double) * m);
    std::memcpy(c + k, co, sizeof(double) * m);
  }
}

void atan2_avx2(const double* y, const double* x, double* out, long n) {
  long k = 0;
  for (; k + 4 <= n; k += 4)
    _mm256_storeu_pd(out + k, Sleef_atan2d4_u10avx2(_mm256_loadu_pd(y + k), _mm256_loadu_pd(x + k)));
  if (k < n) {
    const size_t m = static_cast<size_t>(n - k);
    double yi[4] = {0.0, 0.0, 0.0, 0.0}, xi[4] = {1.0, 1.0, 1.0, 1.0}, o[4];
    std::memcpy(yi, y + k, sizeof(double) * m);
    std::memcpy(xi, x + k, sizeof(double) * m);
    _mm256_storeu_pd(o, Sleef_atan2d4_u10avx2(_mm256_loadu_pd(yi), _mm256_loadu_pd(xi)));
    std::memcpy(out + k, o, sizeof(double) * m);
  }
}

}  // namespace vmath

}  // namespace robokin
