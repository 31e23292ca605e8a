// The array loops behind fast_math.hpp, written once over a vector type V (V::width doubles;
// V::sincos and V::atan2 on one vector): whole vectors, then the tail through a padded vector, so
// that every element goes through the same routine (one padded_map for both). Instantiated for
// SSE2 in fast_math.cpp, for AVX2 + FMA in fast_math_avx2.cpp and for AVX-512 in
// fast_math_avx512.cpp, each compiled for its ISA: the templates sit in an unnamed namespace and
// call no library code, so no copy built for one ISA can stand in for another.
#pragma once

namespace robokin {

namespace vmath {

namespace {

// op(in, out) on W values: in[i] and out[j] point at W doubles each. Whole vectors of the arrays,
// then the tail copied into vectors padded with pad[i] (values the routine takes without fuss).
template <int W, int In, int Out, class Op>
void padded_map(const double* const (&in)[In], const double (&pad)[In], double* const (&out)[Out], long n, Op op) {
  long k = 0;
  for (; k + W <= n; k += W) {
    const double* vi[In];
    double* vo[Out];
    for (int i = 0; i < In; ++i) vi[i] = in[i] + k;
    for (int j = 0; j < Out; ++j) vo[j] = out[j] + k;
    op(vi, vo);
  }
  if (k == n) return;
  const int m = static_cast<int>(n - k);  // plain loops, no library call: short tails are common
  double ti[In][W], to[Out][W];
  const double* vi[In];
  double* vo[Out];
  for (int i = 0; i < In; ++i) {
    for (int j = 0; j < W; ++j) ti[i][j] = j < m ? in[i][k + j] : pad[i];
    vi[i] = ti[i];
  }
  for (int j = 0; j < Out; ++j) vo[j] = to[j];
  op(vi, vo);
  for (int o = 0; o < Out; ++o)
    for (int j = 0; j < m; ++j) out[o][k + j] = to[o][j];
}

template <class V>
void sincos_loop(const double* x, double* s, double* c, long n) {
  padded_map<V::width, 1, 2>({x}, {0.0}, {s, c}, n,
                             [](const double* const* i, double* const* o) { V::sincos(i[0], o[0], o[1]); });
}

template <class V>
void atan2_loop(const double* y, const double* x, double* out, long n) {
  padded_map<V::width, 2, 1>({y, x}, {0.0, 1.0}, {out}, n,
                             [](const double* const* i, double* const* o) { V::atan2(i[0], i[1], o[0]); });
}

}  // namespace

}  // namespace vmath

}  // namespace robokin
