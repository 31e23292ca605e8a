// The lane kernel: a chain's evaluation path (fk_path.hpp) on N "lanes", N configurations at once,
// stored as structure of arrays, so that every step below is a plain loop over the lanes that the
// compiler vectorises (SSE2 is enough) for a batch block, and unrolls to straight scalar code for
// N = 1. Both run the same floating-point operations lane by lane, so a batch gives bit for bit the
// single results. Its steps are forced inline (ROBOKIN_KERNEL, isa.hpp) into fk_batch.cpp's
// entry points and their per-ISA builds, the only file that includes it.
#pragma once

#include "fast_math.hpp"
#include "fk_path.hpp"
#include "isa.hpp"

#include <algorithm>

namespace robokin {

namespace kernel {

constexpr int kBlock = 32;  // lanes of a batch block
constexpr long kJointMajor = -1;  // run_lanes' stride for joint values stored joint by joint

// The products of run_lanes on N lanes, each lane's operations as a single call's. Restrict on
// parameters (which GCC honours, where it ignores it on local pointers): else the fully unrolled
// lanes of fk_few stay scalar.
// x, y <- c x + s y, c y - s x (a row of R turned by a joint's rotation about z).
template <int N>
ROBOKIN_KERNEL void turn_lanes(double* __restrict x, double* __restrict y, const double* __restrict c,
                               const double* __restrict s) {
  for (int k = 0; k < N; ++k) {
    const double xk = x[k], yk = y[k];
    x[k] = c[k] * xk + s[k] * yk;
    y[k] = c[k] * yk - s[k] * xk;
  }
}

// p += v (r a) (a prismatic joint's travel along its axis).
template <int N>
ROBOKIN_KERNEL void slide_lanes(double* __restrict p, const double* __restrict v, const double* __restrict r,
                                double a) {
  for (int k = 0; k < N; ++k) p[k] += v[k] * (r[k] * a);
}

// p += r f (a fixed frame's translation).
template <int N>
ROBOKIN_KERNEL void move_lanes(double* __restrict p, const double* __restrict r, double f) {
  for (int k = 0; k < N; ++k) p[k] += r[k] * f;
}

// (x, y, z) <- (x, y, z) F (a row of R times a fixed frame's rotation).
template <int N>
ROBOKIN_KERNEL void rotate_lanes(double* __restrict x, double* __restrict y, double* __restrict z,
                                 const Eigen::Matrix3d& F) {
  for (int k = 0; k < N; ++k) {
    const double xk = x[k], yk = y[k], zk = z[k];
    x[k] = xk * F(0, 0) + yk * F(1, 0) + zk * F(2, 0);
    y[k] = xk * F(0, 1) + yk * F(1, 1) + zk * F(2, 1);
    z[k] = xk * F(0, 2) + yk * F(1, 2) + zk * F(2, 2);
  }
}

template <int N>
struct Lanes {
  double R[9][N];  // R(i, j) in R[3 * i + j]
  double p[3][N];
};

// run_lanes' hook after each joint: none.
struct NoHook {
  void operator()(int) const {}
};

// The chain on N lanes: joint i of lane k is q[k * stride + i], or q[i * N + k] with stride =
// kJointMajor (a batch block gathered joint by joint). When axes is given (N = 1), the point and z
// axis of every joint after its motion are stored there: axes[6 i .. 6 i + 5]. When turns is given
// (N <= Chain::kFkFew, every joint revolute of scale 1: path.turns), the joints' motions are read
// from their cosines turns[i * N + k] and sines turns[(dof + i) * N + k], and q is not read.
template <int N, class AfterJoint = NoHook>
ROBOKIN_KERNEL void run_lanes(const FkPath& path, Lanes<N>& L, const double* q, long stride, double* axes,
                              AfterJoint after_joint = {}, const double* turns = nullptr) {
  const int dof = path.dof();
  const std::vector<Link>& links = path.links;
  double v[N], s[N], c[N];
  // Up to kAtOnce lanes x joints (one configuration of up to 32 joints, fk_few's 8 of up to 32):
  // the sines and cosines of all revolute joints first, in one vectorised pass (they do not depend
  // on the chain product, which then runs without waiting for them); a value gives the same bits
  // in any pass. (Batch blocks measured no faster this way: benchmarks/README.md.)
  constexpr int kAtOnce = 256;
  double v1[kAtOnce], s1[kAtOnce], c1[kAtOnce];
  const bool all_at_once = N * dof <= kAtOnce && N <= Chain::kFkFew && stride != kJointMajor;
  const double* c_at = turns ? turns : c1;  // the cosines and sines of the joints at once
  const double* s_at = turns ? turns + N * dof : s1;
  if (all_at_once && !turns) {
    int m = 0;
    for (int joint = 0; joint < dof; ++joint) {
      if (links[joint].prismatic && N > 1) continue;
      for (int k = 0; k < N; ++k) v1[m + k] = links[joint].scale * q[k * stride + joint];
      m += N;
    }
    vmath::sincos(v1, s1, c1, m);
  }
  int at = 0;  // the next joint's first value in v1, s1, c1
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) std::fill_n(L.R[3 * i + j], N, path.base.R(i, j));
    std::fill_n(L.p[i], N, path.base.p(i));
  }
  for (int joint = 0; joint < dof; ++joint) {
    const Link& link = links[joint];
    const double* vj = v;  // the joint's values, sines and cosines, lane by lane
    const double* sj = s;
    const double* cj = c;
    if (all_at_once && (N == 1 || !link.prismatic)) {
      vj = v1 + at, sj = s_at + at, cj = c_at + at;
      at += N;
    } else {  // a prismatic joint of several lanes (its values only), or too many values at once
      if (stride == kJointMajor) {
        for (int k = 0; k < N; ++k) v[k] = link.scale * q[joint * N + k];
      } else {
        for (int k = 0; k < N; ++k) v[k] = link.scale * q[k * stride + joint];
      }
      if (!all_at_once && !link.prismatic) vmath::sincos(v, s, c, N);
    }
    if (link.prismatic) {
      // T <- T * Tr(v axis): p moves along R axis (the terms that can be non-zero).
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (link.slide >> (3 * i + j) & 1u) {
            const double a = link.axis(j);
            slide_lanes<N>(L.p[i], vj, L.R[3 * i + j], a);
          }
    } else {
      // T <- T * Rz(v): the x and y columns of R turn by v.
      for (int i = 0; i < 3; ++i) {
        if (!(link.rows >> i & 1u)) continue;
        turn_lanes<N>(L.R[3 * i], L.R[3 * i + 1], cj, sj);
      }
    }
    if (axes) {  // the joint's point and direction (z, or the sliding axis) in the base frame
      for (int r = 0; r < 3; ++r) {
        axes[6 * joint + r] = L.p[r][0];
        axes[6 * joint + 3 + r] = link.prismatic ? L.R[3 * r][0] * link.axis(0) + L.R[3 * r + 1][0] * link.axis(1) +
                                                       L.R[3 * r + 2][0] * link.axis(2)
                                                 : L.R[3 * r + 2][0];
      }
    }
    // T <- T * after: p += R after.p, then R = R after.R (the terms that can change anything).
    const Fixed& f = link.after;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        if (link.move >> (3 * i + j) & 1u) move_lanes<N>(L.p[i], L.R[3 * i + j], f.F.p(j));
      if (link.turn >> i & 1u) rotate_lanes<N>(L.R[3 * i], L.R[3 * i + 1], L.R[3 * i + 2], f.F.R);
    }
    after_joint(joint);
  }
}

template <int N>
inline void lane_to_rigid(const Lanes<N>& L, int k, Rigid& T) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) T.R(i, j) = L.R[3 * i + j][k];
    T.p(i) = L.p[i][k];
  }
}

template <int N>
ROBOKIN_KERNEL void lanes_to_4x4(const Lanes<N>& L, int count, double* m) {
  for (int k = 0; k < count; ++k, m += 16) {
    for (int r = 0; r < 3; ++r) {
      m[4 * r + 0] = L.R[3 * r + 0][k];
      m[4 * r + 1] = L.R[3 * r + 1][k];
      m[4 * r + 2] = L.R[3 * r + 2][k];
      m[4 * r + 3] = L.p[r][k];
    }
    m[12] = m[13] = m[14] = 0.0;
    m[15] = 1.0;
  }
}

// The tool points only: (x, y, z) per lane.
template <int N>
ROBOKIN_KERNEL void lanes_to_position(const Lanes<N>& L, int count, double* m) {
  for (int k = 0; k < count; ++k, m += 3) m[0] = L.p[0][k], m[1] = L.p[1][k], m[2] = L.p[2][k];
}

// True when the first `count` lanes hold finite numbers only: x - x is 0 for a finite x and NaN
// for an infinite or NaN one, and NaN survives the sum. Only p can overflow: R is a product of
// rotations (sines and cosines of finite q, which the caller checks, and orthonormal fixed frames).
template <int N>
ROBOKIN_KERNEL bool lanes_finite(const Lanes<N>& L, int count) {
  double acc[N] = {};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < count; ++k) acc[k] += L.p[i][k] - L.p[i][k];
  double sum = 0.0;
  for (int k = 0; k < count; ++k) sum += acc[k];
  return sum == 0.0;
}

// Writes the first `count` lanes as `what` at out (the output of configuration 0 of the lanes).
template <int N>
ROBOKIN_KERNEL void lanes_store(const Lanes<N>& L, int count, FkOutput what, double* out) {
  if (what == FkOutput::Position) lanes_to_position(L, count, out);
  else lanes_to_4x4(L, count, out);
}

// True when the `count` values at q are finite (x - x is 0 for a finite x, NaN otherwise): the
// batch checks its joint values in the pass that reads them, not in a pass of its own.
ROBOKIN_KERNEL bool values_finite(const double* q, long count) {
  constexpr int kAcc = 16;  // independent sums (four AVX2 vectors): the loop does not wait on one
  double acc[kAcc] = {};
  long i = 0;
  for (; i + kAcc <= count; i += kAcc)
    for (int k = 0; k < kAcc; ++k) acc[k] += q[i + k] - q[i + k];
  for (; i < count; ++i) acc[0] += q[i] - q[i];
  double sum = 0.0;
  for (int k = 0; k < kAcc; ++k) sum += acc[k];
  return sum == 0.0;
}

// One configuration, Chain's hot single calls: the tool frame; with `axes`, also each joint's point
// and direction (z, or the sliding axis) after its motion, axes[6 i .. 6 i + 5].
inline void fk(const FkPath& path, const double* q, Rigid& T, double* axes = nullptr) {
  Lanes<1> L;
  run_lanes<1>(path, L, q, 0, axes);
  lane_to_rigid(L, 0, T);
}

}  // namespace kernel

}  // namespace robokin
