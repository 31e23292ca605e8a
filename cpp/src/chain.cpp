#include "robokin/chain.hpp"

#include "robokin/parallel.hpp"

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace robokin {
namespace {

Rigid to_rigid(const KDL::Frame& f) {
  Rigid r;
  for (int i = 0; i < 3; ++i) {
    r.p(i) = f.p(i);
    for (int j = 0; j < 3; ++j) r.R(i, j) = f.M(i, j);
  }
  return r;
}

KDL::Frame to_kdl(const Matrix4& m) {
  return KDL::Frame(KDL::Rotation(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0),
                                  m(2, 1), m(2, 2)),
                    KDL::Vector(m(0, 3), m(1, 3), m(2, 3)));
}

KDL::JntArray to_jnt(const Vector& q) {
  KDL::JntArray j(static_cast<unsigned>(q.size()));
  j.data = q;
  return j;
}

// A frame at `origin` whose z axis is `axis` (exactly the identity rotation for +z, as in DH chains).
Rigid frame_with_z(const Eigen::Vector3d& axis, const Eigen::Vector3d& origin) {
  Rigid g;
  g.p = origin;
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

void check_limits(int dof, Vector& lower, Vector& upper) {
  const double inf = std::numeric_limits<double>::infinity();
  if (lower.size() == 0 && upper.size() == 0) {
    lower = Vector::Constant(dof, -inf);
    upper = Vector::Constant(dof, inf);
    return;
  }
  if (lower.size() != dof || upper.size() != dof)
    throw std::invalid_argument("limits: expected (lower, upper) with " + std::to_string(dof) +
                                " values each, got " + std::to_string(lower.size()) + " and " +
                                std::to_string(upper.size()));
  for (int i = 0; i < dof; ++i) {
    if (std::isnan(lower(i)) || std::isnan(upper(i)))
      throw std::invalid_argument("limits: joint " + std::to_string(i) + " has a NaN limit");
    if (lower(i) > upper(i))
      throw std::invalid_argument("limits: joint " + std::to_string(i) +
                                  " has its lower limit above its upper limit");
  }
}

}  // namespace

Matrix4 Rigid::matrix() const {
  Matrix4 m = Matrix4::Identity();
  m.topLeftCorner<3, 3>() = R;
  m.topRightCorner<3, 1>() = p;
  return m;
}

Rigid Rigid::from_matrix(const Matrix4& m) { return {m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()}; }

Chain::Chain(KDL::Chain chain, const Vector& lower, const Vector& upper)
    : kdl_(std::move(chain)), dof_(static_cast<int>(kdl_.getNrOfJoints())), lower_(lower), upper_(upper) {
  if (dof_ == 0) throw std::invalid_argument("chain: a chain needs at least one joint");
  check_limits(dof_, lower_, upper_);
  build_fast_path();
}

Chain Chain::from_dh(const std::vector<DHRow>& rows, bool modified, const Matrix4& tool,
                     const Vector& lower, const Vector& upper) {
  KDL::Chain c;
  for (const DHRow& r : rows) {
    const KDL::Joint joint(r.prismatic ? KDL::Joint::TransZ : KDL::Joint::RotZ);
    if (!modified) {
      // Rz(q) Rz(theta) Tz(d) Tx(a) Rx(alpha): the joint adds q to theta (or d; Tz commutes with Rz).
      c.addSegment(KDL::Segment(joint, KDL::Frame::DH(r.a, r.alpha, r.d, r.theta)));
    } else {
      // Rx(alpha) Tx(a) is fixed and comes before the joint: a segment of its own.
      if (r.a != 0.0 || r.alpha != 0.0)
        c.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::Fixed),
                                  KDL::Frame(KDL::Rotation::RotX(r.alpha), KDL::Vector(r.a, 0, 0))));
      c.addSegment(KDL::Segment(joint, KDL::Frame(KDL::Rotation::RotZ(r.theta), KDL::Vector(0, 0, r.d))));
    }
  }
  if (!tool.isIdentity(0.0)) c.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::Fixed), to_kdl(tool)));
  return Chain(std::move(c), lower, upper);
}

Chain Chain::from_segments(const std::vector<SegmentSpec>& segments, const Matrix4& tool,
                           const Vector& lower, const Vector& upper) {
  KDL::Chain c;
  for (const SegmentSpec& s : segments) {
    const KDL::Vector axis(s.axis.x(), s.axis.y(), s.axis.z());
    const KDL::Vector origin = KDL::Vector::Zero();
    KDL::Joint joint(KDL::Joint::Fixed);
    if (s.type == JointType::Revolute) joint = KDL::Joint(origin, axis, KDL::Joint::RotAxis);
    if (s.type == JointType::Prismatic) joint = KDL::Joint(origin, axis, KDL::Joint::TransAxis);
    c.addSegment(KDL::Segment(joint, to_kdl(s.tip)));
  }
  if (!tool.isIdentity(0.0)) c.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::Fixed), to_kdl(tool)));
  return Chain(std::move(c), lower, upper);
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
      since_motion = since_motion * to_rigid(seg.pose(0.0));
      continue;
    }
    const bool prismatic = joint.getType() >= KDL::Joint::TransAxis;
    const KDL::Vector a = joint.JointAxis(), o = joint.JointOrigin();
    const Eigen::Vector3d axis(a.x(), a.y(), a.z());
    const Rigid G = frame_with_z(axis, prismatic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(o.x(), o.y(), o.z()));
    const Rigid P0 = to_rigid(joint.pose(0.0)), P1 = to_rigid(joint.pose(1.0));
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
    else links_.back().after = before;
    links_.push_back({prismatic, scale, Rigid()});
    since_motion = G.inverse() * P0.inverse() * to_rigid(seg.pose(0.0));
  }
  links_.back().after = since_motion;
}

namespace {
// T <- T * Mz(v): rotation about the local z axis, or translation along it.
inline void apply_motion(Rigid& T, bool prismatic, double v) {
  if (prismatic) {
    T.p += v * T.R.col(2);
  } else {
    const double c = std::cos(v), s = std::sin(v);
    const Eigen::Vector3d x = T.R.col(0), y = T.R.col(1);
    T.R.col(0) = c * x + s * y;
    T.R.col(1) = c * y - s * x;
  }
}
inline void apply_fixed(Rigid& T, const Rigid& F) {
  T.p += T.R * F.p;
  T.R = T.R * F.R;
}
}  // namespace

void Chain::fk(const double* q, Rigid& T) const {
  T = base_;
  for (int i = 0; i < dof_; ++i) {
    const Link& L = links_[i];
    apply_motion(T, L.prismatic, L.scale * q[i]);
    apply_fixed(T, L.after);
  }
}

void Chain::fk_jacobian(const double* q, Rigid& T, double* jac) const {
  Eigen::Map<Matrix6X> J(jac, 6, dof_);
  T = base_;
  for (int i = 0; i < dof_; ++i) {
    const Link& L = links_[i];
    apply_motion(T, L.prismatic, L.scale * q[i]);
    // Stash the joint axis (z) and the point it passes through; columns are finished below.
    J.col(i).head<3>() = T.p;
    J.col(i).tail<3>() = T.R.col(2);
    apply_fixed(T, L.after);
  }
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

void Chain::fk_batch(const double* q, long count, double* out) const {
  parallel_for(count, 20000, [&](long begin, long end) {
    Rigid T;
    for (long k = begin; k < end; ++k) {
      fk(q + k * dof_, T);
      double* m = out + 16 * k;
      for (int r = 0; r < 3; ++r) {
        m[4 * r + 0] = T.R(r, 0);
        m[4 * r + 1] = T.R(r, 1);
        m[4 * r + 2] = T.R(r, 2);
        m[4 * r + 3] = T.p(r);
      }
      m[12] = m[13] = m[14] = 0.0;
      m[15] = 1.0;
    }
  });
}

Matrix4 Chain::fk_kdl(const Vector& q) const {
  KDL::ChainFkSolverPos_recursive solver(kdl_);
  KDL::Frame f;
  if (solver.JntToCart(to_jnt(q), f) < 0) throw std::runtime_error("KDL forward kinematics failed");
  return to_rigid(f).matrix();
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
      out.push_back(to_rigid(T).matrix());
    }
  }
  out.back() = to_rigid(T).matrix();  // trailing fixed segments (the tool) belong to the last frame
  return out;
}

}  // namespace robokin
