#include "robokin/chain.hpp"

#include "robokin/limits.hpp"
#include "robokin/parallel.hpp"

#include "chain_lazy.hpp"
#include "kernel/fk_lanes.hpp"
#include "kernel/fk_path.hpp"

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace robokin {
namespace {

KDL::JntArray to_jnt(const Vector& q) {
  KDL::JntArray j(static_cast<unsigned>(q.size()));
  j.data = q;
  return j;
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
    : kdl_(std::move(chain)), dof_(static_cast<int>(kdl_.getNrOfJoints())), limits_{lower, upper, {}} {
  if (dof_ == 0) throw std::invalid_argument("chain: a chain needs at least one joint");
  validate_limits(dof_, limits_.lower, limits_.upper);
  if (limits_.lower.size() == 0) {
    limits_.lower = Vector::Constant(dof_, -INFINITY);
    limits_.upper = Vector::Constant(dof_, INFINITY);
  }
  for (const KDL::Segment& s : kdl_.segments) records_.push_back(SegmentRecord::of(s));
  // Rewritten as base * Mz(s_1 q_1) * after_1 * ... * Mz(s_n q_n) * after_n, where Mz is a
  // rotation about (or translation along) the local z axis: each joint then costs one sin/cos pair
  // and one rigid product (kernel/fk_path.cpp).
  path_ = std::make_shared<const kernel::FkPath>(kernel::build_fk_path(kdl_));
  for (int i = 0; i < dof_; ++i) limits_.prismatic.push_back(prismatic(i));
  planar_ = moves_in_base_plane();
  lazy_ = std::make_shared<Lazy>();
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

bool Chain::moves_in_base_plane() const {
  const Vector zero = Vector::Zero(dof_);
  Matrix6X J(6, dof_);
  Rigid T;
  fk_jacobian(zero.data(), T, J.data());
  constexpr double kTol = 1e-9;  // relative to the column's own size (a unit axis, times the joint's scale)
  for (int i = 0; i < dof_; ++i) {
    const bool off = prismatic(i)
                         ? std::abs(J(2, i)) > kTol * J.col(i).head<3>().norm()                       // v_z
                         : J.col(i).segment<2>(3).norm() > kTol * J.col(i).tail<3>().norm();           // w_x, w_y
    if (off) return false;
  }
  return true;
}

bool Chain::prismatic(int joint) const { return path_->links[joint].prismatic; }

void Chain::fk(const double* q, Rigid& T) const { kernel::fk(*path_, q, T); }

void Chain::fk_jacobian(const double* q, Rigid& T, double* jac) const {
  // Joint axes and points land in the Jacobian's columns (6 per joint, column-major); finished below.
  kernel::fk(*path_, q, T, jac);
  Eigen::Map<Matrix6X> J(jac, 6, dof_);
  const std::vector<kernel::Link>& links = path_->links;
  for (int i = 0; i < dof_; ++i) {
    const Eigen::Vector3d z = J.col(i).tail<3>();
    if (links[i].prismatic) {
      J.col(i).head<3>() = links[i].scale * z;
      J.col(i).tail<3>().setZero();
    } else {
      const Eigen::Vector3d o = J.col(i).head<3>();
      J.col(i).head<3>() = links[i].scale * z.cross(T.p - o);
      J.col(i).tail<3>() = links[i].scale * z;
    }
  }
}

void Chain::fk_few(const double* q, int count, Rigid* out) const { kernel::fk_few(*path_, q, count, out); }
void Chain::fk_few_turns(const double* q, const double* c, const double* s, int count, Rigid* out) const {
  kernel::fk_few_turns(*path_, q, c, s, count, out);
}

bool Chain::fk_batch(const double* q, long count, double* out, FkOutput what, Progress* progress) const {
  return kernel::fk_batch(*path_, q, count, out, what, progress);
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
