// The array loops behind fast_math.hpp, written once over a vector type V (V::width doubles;
// V::sincos and V::atan2 on one vector): whole vectors, then the tail through a padded vector, so
// that every element goes through the same routine. Instantiated for SSE2 in fast_math.cpp and for
// AVX2 + FMA in fast_math_avx2.cpp, which is compiled for that ISA: the templates sit in an unnamed
// namespace and call no inline library code, so no copy built for AVX2 can stand in for the other.
#pragma once

#include <cstring>

namespace robokin {

namespace vmath {

namespace {

template <class V>
void sincos_loop(const double* x, double* s, double* c, long n) {
  constexpr int W = V::width;
  long k = 0;
  for (; k + W <= n; k += W) V::sincos(x + k, s + k, c + k);
  if (k < n) {
    const size_t bytes = sizeof(double) * static_cast<size_t>(n - k);
    double in[W] = {}, so[W], co[W];
    std::memcpy(in, x + k, bytes);
    V::sincos(in, so, co);
    std::memcpy(s + k, so, bytes);
    std::memcpy(c + k, co, bytes);
  }
}

template <class V>
void atan2_loop(const double* y, const double* x, double* out, long n) {
  constexpr int W = V::width;
  long k = 0;
  for (; k + W <= n; k += W) V::atan2(y + k, x + k, out + k);
  if (k < n) {
    const size_t bytes = sizeof(double) * static_cast<size_t>(n - k);
    double yi[W] = {}, xi[W], o[W];
    for (double& v : xi) v = 1.0;
    std::memcpy(yi, y + k, bytes);
    std::memcpy(xi, x + k, bytes);
    V::atan2(yi, xi, o);
    std::memcpy(out + k, o, bytes);
  }
}

}  // namespace

}  // namespace vmath

}  // namespace robokin
