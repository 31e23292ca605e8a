// A task selects what of the tool pose is controlled: rows of the geometric Jacobian
// [v_x v_y v_z w_x w_y w_z] and the matching error between a target and the current pose.
#pragma once

#include "robokin/chain.hpp"

#include <string>

namespace robokin {

enum class Task { Pose, Position, XY, XYPhi };

Task parse_task(const std::string& name);  // "pose" | "position" | "xy" | "xyphi"
const char* task_name(Task task);
int task_rows(Task task);  // 6, 3, 2, 3

// A target for a task: pose -> a rigid frame; position -> (x, y, z); xy -> (x, y); xyphi -> (x, y, phi).
struct Target {
  Task task = Task::XY;
  Rigid pose;             // for Task::Pose
  Eigen::Vector3d value;  // for the others (unused entries zero)
};

// Error (target - current) in task coordinates, rows as task_rows(); the orientation error of a
// pose is the rotation vector of R_target R^T, the planar angle error is wrapped to (-pi, pi].
void task_error(const Target& target, const Rigid& current, double* err);

// Rotation vector (angle * axis, angle in [0, pi]) of a rotation matrix.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R);

// Copies the task's rows of a 6 x n Jacobian into a rows x n one.
template <class Out>
void task_jacobian(Task task, const Matrix6X& J, Out& out) {
  switch (task) {
    case Task::Pose: out = J; return;
    case Task::Position: out = J.topRows(3); return;
    case Task::XY: out = J.topRows(2); return;
    case Task::XYPhi:
      out.resize(3, J.cols());
      out.topRows(2) = J.topRows(2);
      out.row(2) = J.row(5);
      return;
  }
}

// The planar angle of a frame about the base z axis.
inline double planar_angle(const Rigid& T) { return std::atan2(T.R(1, 0), T.R(0, 0)); }

}  // namespace robokin
