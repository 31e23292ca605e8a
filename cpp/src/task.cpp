#include "robokin/task.hpp"
#include "robokin/angles.hpp"

#include "linalg.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace robokin {

Task parse_task(const std::string& name) {
  if (name == "pose") return Task::Pose;
  if (name == "position") return Task::Position;
  if (name == "xy") return Task::XY;
  if (name == "xyphi") return Task::XYPhi;
  throw std::invalid_argument("task: expected one of 'pose', 'position', 'xy', 'xyphi', got '" + name + "'");
}

const char* task_name(Task task) {
  switch (task) {
    case Task::Pose: return "pose";
    case Task::Position: return "position";
    case Task::XY: return "xy";
    case Task::XYPhi: return "xyphi";
  }
  return "?";
}

int task_rows(Task task) {
  switch (task) {
    case Task::Pose: return 6;
    case Task::Position: return 3;
    case Task::XY: return 2;
    case Task::XYPhi: return 3;
  }
  return 0;
}

Task natural_task(const Chain& chain) {
  if (!chain.planar()) return chain.dof() >= 6 ? Task::Pose : Task::Position;
  int revolute = 0;
  for (int i = 0; i < chain.dof(); ++i) revolute += chain.prismatic(i) ? 0 : 1;
  return revolute >= 3 ? Task::XYPhi : Task::XY;
}

// The rotation vector (angle * axis) of R: from the skew part, sin(angle) * axis, and the trace,
// without the quaternion detour of Eigen::AngleAxis (which remains the route near angle = pi).
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d v(0.5 * (R(2, 1) - R(1, 2)), 0.5 * (R(0, 2) - R(2, 0)), 0.5 * (R(1, 0) - R(0, 1)));
  const double c = 0.5 * (R.trace() - 1.0);
  if (c > -0.9) {
    const double s = v.norm();
    return s < 1e-300 ? v : Eigen::Vector3d(v * (std::atan2(s, c) / s));
  }
  const Eigen::AngleAxisd rot(R);
  return rot.angle() * rot.axis();
}

void task_error(const Target& t, const Rigid& T, double* e) {
  switch (t.task) {
    case Task::Pose: {
      const Eigen::Vector3d dp = t.pose.p - T.p;
      const Eigen::Vector3d w = rotation_vector(t.pose.R * T.R.transpose());
      for (int i = 0; i < 3; ++i) e[i] = dp(i), e[3 + i] = w(i);
      return;
    }
    case Task::Position:
      for (int i = 0; i < 3; ++i) e[i] = t.value(i) - T.p(i);
      return;
    case Task::XY:
      e[0] = t.value(0) - T.p(0);
      e[1] = t.value(1) - T.p(1);
      return;
    case Task::XYPhi:
      e[0] = t.value(0) - T.p(0);
      e[1] = t.value(1) - T.p(1);
      e[2] = wrap_angle(t.value(2) - planar_angle(T));
      return;
  }
}

void task_error_norms(Task task, const double* e, double& ep, double& er) {
  using V2 = Eigen::Map<const Eigen::Vector2d>;
  using V3 = Eigen::Map<const Eigen::Vector3d>;
  switch (task) {
    case Task::Pose: ep = safe_norm(V3(e)), er = safe_norm(V3(e + 3)); return;
    case Task::Position: ep = safe_norm(V3(e)), er = 0.0; return;
    case Task::XY: ep = safe_norm(V2(e)), er = 0.0; return;
    case Task::XYPhi: ep = safe_norm(V2(e)), er = std::abs(e[2]); return;
  }
}

}  // namespace robokin
