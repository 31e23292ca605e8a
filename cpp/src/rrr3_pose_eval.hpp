// One evaluation of a 3-RRR pose in a working mode, the only one: RRR3::singularity, the planner
// (rrr3_plan.cpp), connect (rrr3_connect.cpp) and the workspace map (rrr3_workspace.cpp) all read
// the inverse model, the seed's Jacobians A and B, their normalised determinants, the distance to
// parallel singularities and the singularity kind from here. They differ only in what they need:
// the workspace map takes its alpha from RRR3::ik_batch (RRR3::ik's bits, a row of poses at a time)
// and classifies by the determinants alone (measures_at, no distance: an eigenvalue solve per cell
// it never reads); RRR3::singularity throws where a leg cannot reach (ik_or_throw) instead of
// marking the pose unreachable.
#pragma once

#include "robokin/rrr3.hpp"

#include <cmath>
#include <limits>

namespace robokin {

// The seed's A and B at a pose whose actuated angles are known (into the caller's A and B), and
// their determinants, raw and normalised (det A / R_e, det B / l1^3: one tolerance for any robot
// size, RRR3Singularity).
struct PoseMeasures {
  double det_a, det_b, det_a_norm, det_b_norm;
  bool finite;  // A and B are finite
};

inline PoseMeasures measures_at(const RRR3& robot, const Pose& pose, const Eigen::Vector3d& alpha, Eigen::Matrix3d& A,
                                Eigen::Matrix3d& B) {
  robot.jacobians_at(pose, robot.elbows(alpha), A, B);
  PoseMeasures m;
  m.det_a = A.determinant();
  m.det_b = B.determinant();
  // Every entry of A and B enters its determinant (times its cofactor), and the entries are bounded
  // by the robot's lengths: the determinants are finite exactly when A and B are.
  m.finite = std::isfinite(m.det_a) && std::isfinite(m.det_b);
  m.det_a_norm = m.det_a / robot.platform_radius();
  m.det_b_norm = m.det_b / (robot.l1() * robot.l1() * robot.l1());
  return m;
}

// The seed's classification on the normalised determinants: a serial singularity first (a leg
// stretched or folded), then a parallel one.
enum class SingularKind { None, Parallel, Serial };

inline SingularKind singular_kind(double det_a_norm, double det_b_norm, double tol) {
  return std::abs(det_b_norm) < tol ? SingularKind::Serial
                                    : std::abs(det_a_norm) < tol ? SingularKind::Parallel : SingularKind::None;
}

// A pose in a working mode as the planners see it. Unreachable (a leg cannot reach, or A or B is not
// finite): alpha and every measure NaN but those the inverse model left.
struct PoseEval {
  int leg = -1;  // the first leg that cannot reach, -1 when every leg does
  bool reachable = false;
  double det_a = std::numeric_limits<double>::quiet_NaN();     // det A / R_e
  double det_b = std::numeric_limits<double>::quiet_NaN();     // det B / l1^3
  double distance = std::numeric_limits<double>::quiet_NaN();  // RRR3::distance(A)
  Eigen::Vector3d alpha = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

// The inverse model of the mode at pose, then A and B and the distance to parallel singularities
// (an eigenvalue solve: the callers that only classify use measures_at).
inline PoseEval evaluate_pose(const RRR3& robot, const Pose& pose, const Mode& mode) {
  PoseEval e;
  Eigen::Vector3d alpha;
  e.leg = robot.ik(pose, mode, alpha.data());
  if (e.leg >= 0) return e;
  e.alpha = alpha;
  Eigen::Matrix3d A, B;
  const PoseMeasures m = measures_at(robot, pose, alpha, A, B);
  e.reachable = m.finite;
  e.det_a = m.det_a_norm;
  e.det_b = m.det_b_norm;
  e.distance = robot.distance(A);
  return e;
}

}  // namespace robokin
