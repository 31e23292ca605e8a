// A serial kinematic chain: a KDL::Chain (the model and the reference) plus joint limits and a
// specialised evaluation path for the hot calls (forward kinematics and the Jacobian), which the
// core's kernel (cpp/src/kernel/) builds and runs.
#pragma once

#include "robokin/limits.hpp"
#include "robokin/progress.hpp"

#include <Eigen/Dense>
#include <kdl/chain.hpp>

#include <memory>
#include <string>
#include <vector>

namespace robokin {

using Matrix4 = Eigen::Matrix4d;
using Vector = Eigen::VectorXd;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;  // rows of a batch
using Matrix6X = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// A rigid transform kept as rotation + translation: cheaper to chain than a 4x4 product.
struct Rigid {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();

  Rigid operator*(const Rigid& o) const { return {R * o.R, R * o.p + p}; }
  Rigid inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
  Matrix4 matrix() const;
  static Rigid from_matrix(const Matrix4& m);
  static Rigid from_kdl(const KDL::Frame& f);
};

// One row of a Denavit-Hartenberg table; `prismatic` says which of theta / d the joint moves.
struct DHRow {
  double a = 0, alpha = 0, d = 0, theta = 0;
  bool prismatic = false;
};

// One KDL segment given directly: a joint at the segment's start, then a fixed frame to its tip.
enum class JointType { Revolute, Prismatic, Fixed };
struct SegmentSpec {
  JointType type = JointType::Fixed;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // in the segment's start frame, through its origin
  Matrix4 tip = Matrix4::Identity();                 // joint frame -> segment tip
};

// KDL's name for a segment or joint made without one.
inline const char* const kUnnamed = "NoName";

// How one KDL segment was made: the arguments of its constructors. A chain keeps one per segment so
// that it can be rebuilt bit for bit (pickling, copies): KDL normalises a joint axis when it is
// constructed and keeps the tip relative to the joint, so its accessors alone need not give back
// the same numbers.
struct SegmentRecord {
  std::string name = kUnnamed, joint_name = kUnnamed;
  int type = 8;  // a KDL::Joint::JointType (8: Fixed)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // RotAxis / TransAxis joints only
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // as given (KDL normalises it)
  Matrix4 tip = Matrix4::Identity();                 // the frame given to KDL::Segment
  KDL::Segment segment() const;  // throws std::invalid_argument for a bad type or axis
  static SegmentRecord of(const KDL::Segment& segment);  // from KDL's accessors (to within rounding)
};

// The DH table of a chain built from one (kept to show it and to rebuild the chain from it).
struct DHTable {
  std::vector<DHRow> rows;
  bool modified = false;
  Matrix4 tool = Matrix4::Identity();
};

// What a batch FK writes per configuration: the tool frame (4 x 4, row-major) or its point (x, y, z).
enum class FkOutput { Frame, Position };

class IkStarts;  // IK's restart configurations (cpp/src/ik_starts.hpp)
struct ClosedLayout;  // the layout of a closed form of its own (robokin/ik_closed.hpp)

namespace kernel {
struct FkPath;  // the evaluation path (cpp/src/kernel/fk_path.hpp)
}  // namespace kernel

class Chain {
 public:
  // Standard DH: A = Rz(theta) Tz(d) Tx(a) Rx(alpha); modified (Craig): A = Rx(alpha) Tx(a) Rz(theta) Tz(d).
  static Chain from_dh(const std::vector<DHRow>& rows, bool modified, const Matrix4& tool,
                       const Vector& lower, const Vector& upper);
  static Chain from_segments(const std::vector<SegmentSpec>& segments, const Matrix4& tool,
                             const Vector& lower, const Vector& upper);
  // The chain whose segments are made from `records` (bit for bit the chain they were taken from);
  // `base_name` names the link the first segment starts from (empty: unnamed).
  static Chain from_records(const std::vector<SegmentRecord>& records, const Vector& lower, const Vector& upper,
                            const std::string& base_name = "");
  // Wraps an existing KDL chain; limits of size dof or empty for none. Its records are read back
  // from KDL (to within rounding): from_records is the exact route.
  Chain(KDL::Chain chain, const Vector& lower, const Vector& upper);

  // What the chain was built from: one record per KDL segment; the DH table (null unless from_dh).
  const std::vector<SegmentRecord>& records() const { return records_; }
  const DHTable* dh() const { return dh_.rows.empty() ? nullptr : &dh_; }
  // Same kinematics: the same joint types, limits and constant frames of the evaluation path,
  // bit for bit (names and how fixed frames were split into segments do not matter).
  bool same_kinematics(const Chain& other) const;
  std::size_t kinematics_hash() const;  // equal for chains of the same kinematics

  int dof() const { return dof_; }
  const Vector& lower() const { return limits_.lower; }
  const Vector& upper() const { return limits_.upper; }
  bool prismatic(int joint) const;
  // Every joint moves the tool in planes parallel to the base xy plane: revolute axes along the
  // base z axis, prismatic axes perpendicular to it (rows v_z, w_x, w_y of the Jacobian zero; read
  // at q = 0, which decides for every q: turns about z keep the axes' angles with z). natural_task
  // (task.hpp) reads it.
  bool planar() const { return planar_; }
  // The limits as the closed forms take them (lower, upper and which joints are prismatic), held
  // by the chain: a call reads them in place.
  const JointLimits& limits() const { return limits_; }
  const KDL::Chain& kdl() const { return kdl_; }

  // Names, read from the records (a URDF chain's are the file's). joint_names: the dof moving
  // joints'. link_names (dof + 1): the link of each frame of frames(q): the base link, the link
  // each joint 1 .. dof-1 moves (the segment it heads), then the chain's last link (the tip, after
  // any fixed segments: a flange, a tool). Parts without a name (DH tables, plain segments) are
  // called q1 .. qn, base and link1 .. linkn. named(): some name came with the chain.
  std::vector<std::string> joint_names() const;
  std::vector<std::string> link_names() const;
  const std::string& base_name() const { return base_name_; }
  bool named() const;

  // Fast path (no allocation): tool pose, and the 6 x dof geometric Jacobian at the tool point.
  void fk(const double* q, Rigid& out) const;
  void fk_jacobian(const double* q, Rigid& out, double* jac_colmajor_6xn) const;
  // count <= kFkFew configurations (count x dof, row-major) evaluated together, one pass of the
  // batch kernel: out[k] has the bits fk gives for row k (for the closed forms' checks).
  static constexpr int kFkFew = 8;
  void fk_few(const double* q, int count, Rigid* out) const;
  // fk_few of q, each joint's motion read from its turn where every joint is revolute (c, s: the
  // cosines and sines of q's angles, rows as q's): the closed forms' check of the candidates they
  // hold as turns, without a pass of sines and cosines.
  void fk_few_turns(const double* q, const double* c, const double* s, int count, Rigid* out) const;
  // count configurations (count x dof, row-major) -> count frames (16 values each) or points (3);
  // false when some joint value or some result is not finite (lengths near overflow): the joint
  // values are checked here, in the pass that reads them.
  bool fk_batch(const double* q, long count, double* out, FkOutput what = FkOutput::Frame,
                Progress* progress = nullptr) const;

  // IK's restart configurations (cpp/src/ik_starts.hpp): built at the first call (thread-safe), then
  // shared by the chain's copies; a chain unpickled builds the same again.
  const IkStarts& ik_starts() const;
  // The layout of a closed form of its own (UR, spherical wrist; robokin/ik_closed.hpp), read from
  // the geometry at the first call (thread-safe), then shared by the chain's copies: a closed form
  // called per pose pays the reading once.
  const ClosedLayout& closed_layout() const;

  // KDL's recursive solvers: the reference, and the frames of every joint segment.
  Matrix4 fk_kdl(const Vector& q) const;
  Matrix6X jacobian_kdl(const Vector& q) const;
  std::vector<Matrix4> frames(const Vector& q) const;  // base, frame 1..dof (last: tool applied)
  // A point given in frame `frame` (an index into frames(q)) expressed in frame `in_frame`.
  Eigen::Vector3d point_in_frame(const Vector& q, const Eigen::Vector3d& point, int frame, int in_frame) const;

 private:
  bool moves_in_base_plane() const;  // planar(), from the Jacobian at q = 0

  KDL::Chain kdl_;
  std::vector<SegmentRecord> records_;
  DHTable dh_;
  std::string base_name_;
  int dof_ = 0;
  JointLimits limits_;  // no limits: -inf and +inf
  // Built once by the constructor, never changed: copies share it, const calls only read it.
  std::shared_ptr<const kernel::FkPath> path_;
  bool planar_ = false;
  struct Lazy;  // derived data built at first use (ik_starts.hpp)
  std::shared_ptr<Lazy> lazy_;
};

}  // namespace robokin
