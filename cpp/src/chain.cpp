#include "robokin/chain.hpp"

#include "robokin/limits.hpp"
#include "robokin/parallel.hpp"

#include "kernel/fast_math.hpp"
#include "kernel/isa.hpp"
#include "kernel/paging.hpp"

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace robokin {
namespace {

KDL::JntArray to_jnt(const Vector& q) {
  KDL::JntArray j(static_cast<unsigned>(q.size()));
  j.data = q;
  return j;
}

// A rotation whose z axis is `axis` (exactly the identity for +z, as in DH chains).
Rigid frame_with_z(const Eigen::Vector3d& axis) {
  Rigid g;
  const Eigen::Vector3d z = axis.normalized();
  if (z.isApprox(Eigen::Vector3d::UnitZ(), 1e-15)) return g;
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d y = z.cross(helper).normalized();
  g.R.col(0) = y.cross(z);
  g.R.col(1) = y;
  g.R.col(2) = z;
  return g;
}

}  // namespace

Matrix4 Rigid::matrix() const {
  Matrix4 m = Matrix4::Identity();
  m.topLeftCorner<3, 3>() = R;
  m.topRightCorner<3, 1>() = p;
  return m;
}

Rigid Rigid::from_kdl(const KDL::Frame& f) {
  Rigid r;
  for (int i = 0; i < 3; ++i) {
    r.p(i) = f.p(i);
    for (int j = 0; j < 3; ++j) r.R(i, j) = f.M(i, j);
  }
  return r;
}

Rigid Rigid::from_matrix(const Matrix4& m) { return {m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()}; }

Chain::Chain(KDL::Chain chain, const Vector& lower, const Vector& upper)
    : kdl_(std::move(chain)), dof_(static_cast<int>(kdl_.getNrOfJoints())), lower_(lower), upper_(upper) {
  if (dof_ == 0) throw std::invalid_argument("chain: a chain needs at least one joint");
  validate_limits(dof_, lower_, upper_);
  if (lower_.size() == 0) {
    lower_ = Vector::Constant(dof_, -INFINITY);
    upper_ = Vector::Constant(dof_, INFINITY);
  }
  for (const KDL::Segment& s : kdl_.segments) records_.push_back(SegmentRecord::of(s));
  build_fast_path();
}

Chain Chain::from_dh(const std::vector<DHRow>& rows, bool modified, const Matrix4& tool,
                     const Vector& lower, const Vector& upper) {
  std::vector<SegmentRecord> records;
  for (const DHRow& r : rows) {
    SegmentRecord joint;
    joint.type = r.prismatic ? KDL::Joint::TransZ : KDL::Joint::RotZ;
    if (!modified) {
      // Rz(q) Rz(theta) Tz(d) Tx(a) Rx(alpha): the joint adds q to theta (or d; Tz commutes with Rz).
      joint.tip = Rigid::from_kdl(KDL::Frame::DH(r.a, r.alpha, r.d, r.theta)).matrix();
    } else {
      // Rx(alpha) Tx(a) is fixed and comes before the joint: a segment of its own.
      if (r.a != 0.0 || r.alpha != 0.0) {
        SegmentRecord fixed;
        fixed.tip = Rigid::from_kdl(KDL::Frame(KDL::Rotation::RotX(r.alpha), KDL::Vector(r.a, 0, 0))).matrix();
        records.push_back(fixed);
      }
      joint.tip = Rigid::from_kdl(KDL::Frame(KDL::Rotation::RotZ(r.theta), KDL::Vector(0, 0, r.d))).matrix();
    }
    records.push_back(joint);
  }
  if (!tool.isIdentity(0.0)) records.push_back(SegmentRecord{"NoName", "NoName", KDL::Joint::Fixed, {}, {}, tool});
  Chain chain = from_records(records, lower, upper);
  chain.dh_ = DHTable{rows, modified, tool};
  return chain;
}

Chain Chain::from_segments(const std::vector<SegmentSpec>& segments, const Matrix4& tool,
                           const Vector& lower, const Vector& upper) {
  std::vector<SegmentRecord> records;
  for (const SegmentSpec& s : segments) {
    SegmentRecord r;
    if (s.type == JointType::Revolute) r.type = KDL::Joint::RotAxis;
    if (s.type == JointType::Prismatic) r.type = KDL::Joint::TransAxis;
    r.axis = s.axis;
    r.tip = s.tip;
    records.push_back(r);
  }
  if (!tool.isIdentity(0.0)) records.push_back(SegmentRecord{"NoName", "NoName", KDL::Joint::Fixed, {}, {}, tool});
  return from_records(records, lower, upper);
}

// Rewrites the chain as base * Mz(s_1 q_1) * after_1 * ... * Mz(s_n q_n) * after_n, where Mz is a
// rotation about (or translation along) the local z axis: each joint then costs one sin/cos pair
// and one rigid product.
void Chain::build_fast_path() {
  links_.clear();
  Rigid since_motion;  // fixed transform accumulated since the last joint motion
  for (const KDL::Segment& seg : kdl_.segments) {
    const KDL::Joint& joint = seg.getJoint();
    if (joint.getType() == KDL::Joint::Fixed) {
      since_motion = since_motion * Rigid::from_kdl(seg.pose(0.0));
      continue;
    }
    const bool prismatic = joint.getType() >= KDL::Joint::TransAxis;
    const KDL::Vector a = joint.JointAxis();
    const Eigen::Vector3d axis(a.x(), a.y(), a.z());
    // KDL: joint.pose(q) = Frame(Rot(axis, scale q + offset), origin), so joint.pose(q) =
    // P0 * G Mz(scale q) G^-1 with G a rotation taking z to the axis (no translation).
    // A prismatic joint slides along its axis as it is (no turn to z and back).
    const Rigid G = prismatic ? Rigid() : frame_with_z(axis);
    const Rigid P0 = Rigid::from_kdl(joint.pose(0.0)), P1 = Rigid::from_kdl(joint.pose(1.0));
    // The joint's scale: how far one unit of q moves it (1 for every chain robokin builds).
    double scale;
    if (prismatic) {
      scale = (P1.p - P0.p).dot(axis.normalized());
    } else {
      const Eigen::Matrix3d rel = P0.R.transpose() * P1.R;
      const Eigen::Vector3d w(rel(2, 1) - rel(1, 2), rel(0, 2) - rel(2, 0), rel(1, 0) - rel(0, 1));
      scale = std::atan2(0.5 * w.dot(axis.normalized()), 0.5 * (rel.trace() - 1.0));
    }
    if (std::abs(scale - 1.0) < 1e-12) scale = 1.0;
    const Rigid before = since_motion * P0 * G;
    if (links_.empty()) base_ = before;
    else links_.back().after = make_fixed(before);
    links_.push_back({prismatic, scale, prismatic ? axis.normalized() : Eigen::Vector3d::UnitZ(), Fixed()});
    since_motion = G.inverse() * P0.inverse() * Rigid::from_kdl(seg.pose(0.0));
  }
  links_.back().after = make_fixed(since_motion);
  build_masks();
  planar_ = moves_in_base_plane();
}

bool Chain::moves_in_base_plane() const {
  const Vector zero = Vector::Zero(dof_);
  Matrix6X J(6, dof_);
  Rigid T;
  fk_jacobian(zero.data(), T, J.data());
  constexpr double kTol = 1e-9;  // relative to the column's own size (a unit axis, times the joint's scale)
  for (int i = 0; i < dof_; ++i) {
    const bool off = links_[i].prismatic
                         ? std::abs(J(2, i)) > kTol * J.col(i).head<3>().norm()                       // v_z
                         : J.col(i).segment<2>(3).norm() > kTol * J.col(i).tail<3>().norm();           // w_x, w_y
    if (off) return false;
  }
  return true;
}

// Follows which entries of R can be non-zero along the chain (nz), starting from the base.
void Chain::build_masks() {
  bool nz[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) nz[i][k] = base_.R(i, k) != 0.0;
  for (Link& link : links_) {
    link.rows = link.slide = link.move = link.turn = 0;
    for (int i = 0; i < 3; ++i) {
      if (link.prismatic) {
        for (int k = 0; k < 3; ++k)
          if (nz[i][k] && link.axis(k) != 0.0) link.slide |= 1u << (3 * i + k);
      } else if (nz[i][0] || nz[i][1]) {
        link.rows |= 1u << i;
        nz[i][0] = nz[i][1] = true;
      }
    }
    const Fixed& f = link.after;
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k)
        if (f.move && nz[i][k] && f.F.p(k) != 0.0) link.move |= 1u << (3 * i + k);
      if (f.turn && (nz[i][0] || nz[i][1] || nz[i][2])) {
        link.turn |= 1u << i;
        bool row[3];
        for (int j = 0; j < 3; ++j) {
          row[j] = false;
          for (int k = 0; k < 3; ++k) row[j] = row[j] || (nz[i][k] && f.F.R(k, j) != 0.0);
        }
        for (int j = 0; j < 3; ++j) nz[i][j] = row[j];
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The evaluation kernel. It works on N "lanes": N configurations at once, stored as structure of
// arrays, so that every step below is a plain loop over the lanes that the compiler vectorises
// (SSE2 is enough) for a batch block, and unrolls to straight scalar code for N = 1. Both run the
// same floating-point operations lane by lane, so a batch gives bit for bit the single results.

constexpr int kBlock = 32;  // lanes of a batch block
constexpr long kJointMajor = -1;  // run_lanes' stride for joint values stored joint by joint

// The kernel is forced inline into its callers (ROBOKIN_KERNEL, kernel/isa.hpp), so that the batch
// loop is compiled three times: for the baseline ISA (2 doubles per vector), AVX2 (4) and AVX-512
// (8), chosen by detected_isa(). Contraction into fused multiply-adds is turned off in those
// copies, so they round exactly as the baseline: the same results, bit for bit, as single calls.
using kernel::detected_isa;
using kernel::Isa;

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

Chain::Fixed Chain::make_fixed(const Rigid& F) {
  Fixed f;
  f.F = F;
  f.move = !F.p.isZero(0.0);
  f.turn = F.R != Eigen::Matrix3d::Identity();
  return f;
}

// The chain on N lanes: joint i of lane k is q[k * stride + i], or q[i * N + k] with stride =
// kJointMajor (a batch block gathered joint by joint). When axes is given (N = 1), the point and z
// axis of every joint after its motion are stored there: axes[6 i .. 6 i + 5].
template <int N, class AfterJoint>
ROBOKIN_KERNEL void Chain::run_lanes(Lanes<N>& L, const double* q, long stride, double* axes,
                                     AfterJoint after_joint) const {
  double v[N], s[N], c[N];
  // Up to kAtOnce lanes x joints (one configuration of up to 32 joints, fk_few's 8 of up to 32):
  // the sines and cosines of all revolute joints first, in one vectorised pass (they do not depend
  // on the chain product, which then runs without waiting for them); a value gives the same bits
  // in any pass. (Batch blocks measured no faster this way: benchmarks/README.md.)
  constexpr int kAtOnce = 256;
  double v1[kAtOnce], s1[kAtOnce], c1[kAtOnce];
  const bool all_at_once = N * dof_ <= kAtOnce && N <= Chain::kFkFew && stride != kJointMajor;
  if (all_at_once) {
    int m = 0;
    for (int joint = 0; joint < dof_; ++joint) {
      if (links_[joint].prismatic && N > 1) continue;
      for (int k = 0; k < N; ++k) v1[m + k] = links_[joint].scale * q[k * stride + joint];
      m += N;
    }
    vmath::sincos(v1, s1, c1, m);
  }
  int at = 0;  // the next joint's first value in v1, s1, c1
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) std::fill_n(L.R[3 * i + j], N, base_.R(i, j));
    std::fill_n(L.p[i], N, base_.p(i));
  }
  for (int joint = 0; joint < dof_; ++joint) {
    const Link& link = links_[joint];
    const double* vj = v;  // the joint's values, sines and cosines, lane by lane
    const double* sj = s;
    const double* cj = c;
    if (all_at_once && (N == 1 || !link.prismatic)) {
      vj = v1 + at, sj = s1 + at, cj = c1 + at;
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

namespace {
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
#ifdef ROBOKIN_DISPATCH
// The same for a whole block, 4 lanes at a time: each row of R and p transposed in registers into
// the 4 lanes' matrix rows, one 32-byte store per row (48 loads and 16 stores of 8 bytes per lane
// before). The same bits, moved.
ROBOKIN_TARGET_AVX2 void block_to_4x4_avx2(const Lanes<kBlock>& L, double* m) {
  static_assert(kBlock % 4 == 0, "whole vectors of lanes");
  const __m256d last = _mm256_set_pd(1.0, 0.0, 0.0, 0.0);
  for (int k = 0; k < kBlock; k += 4, m += 64) {
    for (int r = 0; r < 3; ++r) {
      const __m256d a = _mm256_loadu_pd(L.R[3 * r] + k), b = _mm256_loadu_pd(L.R[3 * r + 1] + k);
      const __m256d c = _mm256_loadu_pd(L.R[3 * r + 2] + k), d = _mm256_loadu_pd(L.p[r] + k);
      const __m256d ab0 = _mm256_unpacklo_pd(a, b), ab1 = _mm256_unpackhi_pd(a, b);  // lanes 0, 2 | 1, 3
      const __m256d cd0 = _mm256_unpacklo_pd(c, d), cd1 = _mm256_unpackhi_pd(c, d);
      _mm256_storeu_pd(m + 4 * r, _mm256_permute2f128_pd(ab0, cd0, 0x20));
      _mm256_storeu_pd(m + 16 + 4 * r, _mm256_permute2f128_pd(ab1, cd1, 0x20));
      _mm256_storeu_pd(m + 32 + 4 * r, _mm256_permute2f128_pd(ab0, cd0, 0x31));
      _mm256_storeu_pd(m + 48 + 4 * r, _mm256_permute2f128_pd(ab1, cd1, 0x31));
    }
    for (int j = 0; j < 4; ++j) _mm256_storeu_pd(m + 16 * j + 12, last);
  }
}
// Pairs of values (128 bits each) gathered from two vectors of four pairs: x's even pairs, then
// y's; x's odd pairs, then y's.
__attribute__((target("avx512f"), always_inline)) inline __m512d even_pairs(__m512d x, __m512d y) {
  return _mm512_shuffle_f64x2(x, y, 0x88);
}
__attribute__((target("avx512f"), always_inline)) inline __m512d odd_pairs(__m512d x, __m512d y) {
  return _mm512_shuffle_f64x2(x, y, 0xdd);
}
// block_to_4x4_avx2 with AVX-512, 8 lanes at a time: lane k's rows 0 and 1 in one 64-byte store,
// rows 2 and 3 in another (an 8 x 8 transpose of R's rows 0, 1 and p's; a 4 x 8 one completed by
// the constant row). The same bits, moved in fewer, wider stores.
ROBOKIN_TARGET_AVX512 void block_to_4x4_avx512(const Lanes<kBlock>& L, double* m) {
  static_assert(kBlock % 8 == 0, "whole vectors of lanes");
  const __m512d row3 = _mm512_set_pd(1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // (0 0 0 1) unpacked, gathered
  const int lane[4] = {0, 2, 1, 3};  // the first lane of the pairs (even, odd) of each vector below
  for (int k = 0; k < kBlock; k += 8, m += 128) {
    // Rows 0 and 1 as (a b) (c d) pairs: lo[r], lo[2 + r] row r of lanes 0 4 and 2 6; hi[r],
    // hi[2 + r] of lanes 1 5 and 3 7.
    __m512d lo[4], hi[4];
    for (int r = 0; r < 3; ++r) {
      const __m512d a = _mm512_loadu_pd(L.R[3 * r] + k), b = _mm512_loadu_pd(L.R[3 * r + 1] + k);
      const __m512d c = _mm512_loadu_pd(L.R[3 * r + 2] + k), d = _mm512_loadu_pd(L.p[r] + k);
      const __m512d ab_even = _mm512_unpacklo_pd(a, b), ab_odd = _mm512_unpackhi_pd(a, b);
      const __m512d cd_even = _mm512_unpacklo_pd(c, d), cd_odd = _mm512_unpackhi_pd(c, d);
      // Row r of lanes 0, 2 | 4, 6 (even pairs) and 1, 3 | 5, 7 (odd).
      if (r < 2) {
        lo[r] = even_pairs(ab_even, cd_even), lo[2 + r] = odd_pairs(ab_even, cd_even);
        hi[r] = even_pairs(ab_odd, cd_odd), hi[2 + r] = odd_pairs(ab_odd, cd_odd);
        continue;
      }
      const __m512d r2[4] = {even_pairs(ab_even, cd_even), odd_pairs(ab_even, cd_even), even_pairs(ab_odd, cd_odd),
                             odd_pairs(ab_odd, cd_odd)};  // lanes 0 4 | 2 6 | 1 5 | 3 7, rows 2 as pairs
      for (int h = 0; h < 4; ++h) {
        _mm512_storeu_pd(m + 16 * lane[h] + 8, even_pairs(r2[h], row3));
        _mm512_storeu_pd(m + 16 * (lane[h] + 4) + 8, odd_pairs(r2[h], row3));
      }
    }
    // Rows 0 and 1: lanes 0 4 (lo[0], lo[1]), 2 6 (lo[2], lo[3]), 1 5 (hi[0], hi[1]), 3 7 (hi[2], hi[3]).
    const __m512d* pairs[4] = {lo, lo + 2, hi, hi + 2};
    for (int h = 0; h < 4; ++h) {
      _mm512_storeu_pd(m + 16 * lane[h], even_pairs(pairs[h][0], pairs[h][1]));
      _mm512_storeu_pd(m + 16 * (lane[h] + 4), odd_pairs(pairs[h][0], pairs[h][1]));
    }
  }
}
// The joint values of a batch block (kBlock configurations of dof joints at q) joint by joint:
// qT[j * kBlock + k] = q[k * dof + j], 8 lanes per gather. Read with a stride of dof, run_lanes
// loaded them one value at a time (the gain is in benchmarks/README.md).
constexpr int kGatherJoints = 16;
ROBOKIN_TARGET_AVX512 void gather_block_avx512(const double* q, int dof, double* qT) {
  const long d = dof;
  for (int k = 0; k < kBlock; k += 8) {
    const __m512i at = _mm512_set_epi64((k + 7) * d, (k + 6) * d, (k + 5) * d, (k + 4) * d, (k + 3) * d,
                                        (k + 2) * d, (k + 1) * d, k * d);
    for (int j = 0; j < dof; ++j) _mm512_storeu_pd(qT + j * kBlock + k, _mm512_i64gather_pd(at, q + j, 8));
  }
}
#endif

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
}  // namespace

void Chain::fk(const double* q, Rigid& T) const {
  Lanes<1> L;
  run_lanes<1>(L, q, 0, nullptr);
  lane_to_rigid(L, 0, T);
}

void Chain::fk_jacobian(const double* q, Rigid& T, double* jac) const {
  Lanes<1> L;
  // Joint axes and points land in the Jacobian's columns (6 per joint, column-major); finished below.
  run_lanes<1>(L, q, 0, jac);
  lane_to_rigid(L, 0, T);
  Eigen::Map<Matrix6X> J(jac, 6, dof_);
  for (int i = 0; i < dof_; ++i) {
    const Eigen::Vector3d z = J.col(i).tail<3>();
    if (links_[i].prismatic) {
      J.col(i).head<3>() = links_[i].scale * z;
      J.col(i).tail<3>().setZero();
    } else {
      const Eigen::Vector3d o = J.col(i).head<3>();
      J.col(i).head<3>() = links_[i].scale * z.cross(T.p - o);
      J.col(i).tail<3>() = links_[i].scale * z;
    }
  }
}


// Configurations [begin, end) of a batch, in blocks of kBlock lanes; false when a joint value or a
// result is not finite. With `populate`, the output's pages are faulted in ahead of the stores.
ROBOKIN_KERNEL bool Chain::batch_range_kernel(const double* q, long begin, long end, double* out, FkOutput what,
                                              bool populate) const {
  const long width = what == FkOutput::Position ? 3 : 16;
  Lanes<kBlock> L;
  bool finite = true;
  long b = begin, populated = begin;
  auto fault_in = [&](long upto) {
    if (!populate || upto <= populated) return;
    const long to = kernel::next_page_end(out, width, upto, end);
    kernel::populate_for_writing(out + width * populated, out + width * to);
    populated = to;
  };
#ifdef ROBOKIN_DISPATCH
  // A batch block's joint values gathered joint by joint and its frames stored with AVX-512 or AVX2
  // where the CPU has them; else plain loads and stores.
  const Isa isa = detected_isa();
  const bool gather = isa == Isa::Avx512 && dof_ <= kGatherJoints;
  alignas(64) double qT[kGatherJoints * kBlock];
#endif
  for (; b + kBlock <= end; b += kBlock) {
    const double* qb = q + b * dof_;
    const double* lanes_q = qb;  // the block's joint values as run_lanes reads them
    long lanes_stride = dof_;
#ifdef ROBOKIN_DISPATCH
    if (gather) {
      gather_block_avx512(qb, dof_, qT);
      lanes_q = qT, lanes_stride = kJointMajor;
    }
#endif
    if (populate) {
      // The next block's output lines fetched while this one is computed: the kernel's zeroing
      // leaves them out of the first-level caches, and each store waited for its line. A part is
      // asked for before the chain and a part after each joint: all at once, the requests beyond
      // the cache's few outstanding misses stalled the block; two blocks ahead measured slower.
      // Written here, not in a helper: GCC deletes calls to a function whose only effect is a prefetch.
      const long next_end = std::min(end, b + 2 * kBlock);
      fault_in(next_end);
      const char* line = reinterpret_cast<const char*>(out + width * (b + kBlock));
      const char* const stop = reinterpret_cast<const char*>(out + width * next_end);
      const long part = ((stop - line) / 64 / (dof_ + 1) + 1) * 64;  // bytes of lines per part
      auto fetch_part = [&](int /*joint*/) {
        for (const char* e = std::min(stop, line + part); line < e; line += 64) __builtin_prefetch(line, 1, 3);
      };
      fetch_part(-1);  // before the first joint
      run_lanes<kBlock>(L, lanes_q, lanes_stride, nullptr, fetch_part);
    } else {
      run_lanes<kBlock>(L, lanes_q, lanes_stride, nullptr);
    }
    finite &= values_finite(qb, kBlock * dof_) & lanes_finite(L, kBlock);
    fault_in(b + kBlock);
#ifdef ROBOKIN_DISPATCH
    if (what == FkOutput::Frame && isa != Isa::Baseline) {
      if (isa == Isa::Avx512) block_to_4x4_avx512(L, out + width * b);
      else block_to_4x4_avx2(L, out + width * b);
      continue;
    }
#endif
    lanes_store(L, kBlock, what, out + width * b);
  }
  // The tail, one configuration at a time (the same operations as a block lane).
  Lanes<1> one;
  for (; b < end; ++b) {
    run_lanes<1>(one, q + b * dof_, 0, nullptr);
    finite &= values_finite(q + b * dof_, dof_) & lanes_finite(one, 1);
    fault_in(b + 1);
    lanes_store(one, 1, what, out + width * b);
  }
  return finite;
}

bool Chain::batch_range(const double* q, long begin, long end, double* out, FkOutput what, bool populate) const {
  return batch_range_kernel(q, begin, end, out, what, populate);
}

#ifdef ROBOKIN_DISPATCH
ROBOKIN_TARGET_AVX2 ROBOKIN_NO_CONTRACT bool Chain::batch_range_avx2(
    const double* q, long begin, long end, double* out, FkOutput what, bool populate) const {
  return batch_range_kernel(q, begin, end, out, what, populate);
}

ROBOKIN_TARGET_AVX512 ROBOKIN_NO_CONTRACT bool Chain::batch_range_avx512(
    const double* q, long begin, long end, double* out, FkOutput what, bool populate) const {
  return batch_range_kernel(q, begin, end, out, what, populate);
}
#endif

namespace {
constexpr int kFkFewJoints = 32;
}  // namespace

// Every lane is evaluated: the unused ones repeat the first configuration.
ROBOKIN_KERNEL void Chain::fk_few_kernel(const double* q, int count, Rigid* out) const {
  double padded[kFkFew * kFkFewJoints];
  std::copy(q, q + count * dof_, padded);
  for (int k = count; k < kFkFew; ++k) std::copy(q, q + dof_, padded + k * dof_);
  Lanes<kFkFew> L;
  run_lanes<kFkFew>(L, padded, dof_, nullptr);
  for (int k = 0; k < count; ++k) lane_to_rigid(L, k, out[k]);
}

void Chain::fk_few_lanes(const double* q, int count, Rigid* out) const { fk_few_kernel(q, count, out); }

#ifdef ROBOKIN_DISPATCH
ROBOKIN_TARGET_AVX2 ROBOKIN_NO_CONTRACT void Chain::fk_few_avx2(const double* q, int count, Rigid* out) const {
  fk_few_kernel(q, count, out);
}
#endif

void Chain::fk_few(const double* q, int count, Rigid* out) const {
  if (count > kFkFew || dof_ > kFkFewJoints) {  // not for this kernel: one at a time
    for (int k = 0; k < count; ++k) fk(q + k * dof_, out[k]);
    return;
  }
  if (count <= 0) return;
#ifdef ROBOKIN_DISPATCH
  // AVX2 (4 lanes per vector) measured faster than the baseline's 2 for a UR closed-form call; an
  // AVX-512 build of the same kernel did not, so none is made (benchmarks/README.md).
  if (detected_isa() != Isa::Baseline) return fk_few_avx2(q, count, out);
#endif
  fk_few_lanes(q, count, out);
}


bool Chain::fk_batch(const double* q, long count, double* out, FkOutput what, Progress* progress) const {
  // A large frame output (beyond the caches) is faulted in chunk by chunk as it is written.
  const bool populate = what == FkOutput::Frame && count >= 32768;
#ifdef ROBOKIN_DISPATCH
  const Isa isa = detected_isa();
#endif
  std::atomic<bool> finite{true};
  parallel_for(count, 20000, [&](long begin, long end) {
    bool ok;
#ifdef ROBOKIN_DISPATCH
    if (isa == Isa::Avx512) ok = batch_range_avx512(q, begin, end, out, what, populate);
    else if (isa == Isa::Avx2) ok = batch_range_avx2(q, begin, end, out, what, populate);
    else ok = batch_range(q, begin, end, out, what, populate);
#else
    ok = batch_range(q, begin, end, out, what, populate);
#endif
    if (!ok) finite = false;
  }, progress);
  return finite;
}

Matrix4 Chain::fk_kdl(const Vector& q) const {
  KDL::ChainFkSolverPos_recursive solver(kdl_);
  KDL::Frame f;
  if (solver.JntToCart(to_jnt(q), f) < 0) throw std::runtime_error("KDL forward kinematics failed");
  return Rigid::from_kdl(f).matrix();
}

Matrix6X Chain::jacobian_kdl(const Vector& q) const {
  KDL::ChainJntToJacSolver solver(kdl_);
  KDL::Jacobian jac(static_cast<unsigned>(dof_));
  if (solver.JntToJac(to_jnt(q), jac) < 0) throw std::runtime_error("KDL Jacobian failed");
  return jac.data;
}

std::vector<Matrix4> Chain::frames(const Vector& q) const {
  std::vector<Matrix4> out{Matrix4::Identity()};
  KDL::Frame T = KDL::Frame::Identity();
  int j = 0;
  for (const KDL::Segment& seg : kdl_.segments) {
    const bool moves = seg.getJoint().getType() != KDL::Joint::Fixed;
    T = T * seg.pose(moves ? q(j) : 0.0);
    if (moves) {
      ++j;
      out.push_back(Rigid::from_kdl(T).matrix());
    }
  }
  out.back() = Rigid::from_kdl(T).matrix();  // trailing fixed segments (the tool) belong to the last frame
  return out;
}

Eigen::Vector3d Chain::point_in_frame(const Vector& q, const Eigen::Vector3d& point, int frame, int in_frame) const {
  const std::vector<Matrix4> f = frames(q);
  const Matrix4 rel = Rigid::from_matrix(f[in_frame]).inverse().matrix() * f[frame];
  return rel.topLeftCorner<3, 3>() * point + rel.topRightCorner<3, 1>();
}

}  // namespace robokin
