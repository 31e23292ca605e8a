// A task selects what of the tool pose is controlled: rows of the geometric Jacobian
// [v_x v_y v_z w_x w_y w_z] and the matching error between a target and the current pose.
#pragma once

#include "robokin/chain.hpp"

#include <string>

namespace robokin {

enum class Task { Pose, Position, XY, XYPhi };

Task parse_task(const std::string& name);  // "pose" | "position" | "xy" | "xyphi"
const char* task_name(Task task);
// The same as the overloads every named enum of the core has (options fields bind them by name).
inline void parse(const std::string& name, Task& task) { task = parse_task(name); }
inline const char* name_of(Task task) { return task_name(task); }
int task_rows(Task task);  // 6, 3, 2, 3

// The task a call controls when it is given none (task=None in Python), from the chain's geometry:
//   a planar arm (Chain::planar: every joint moves the tool parallel to the base xy plane):
//     "xyphi" with at least three revolute joints, "xy" otherwise;
//   any other arm: "pose" with at least six joints, "position" otherwise.
// A planar arm's tool angle phi is the sum of its revolute angles (a prismatic joint slides the tool,
// it never turns it): three revolute joints set the tip and phi together (the IK course's planar 3R), while
// an arm with fewer positions its tip, a prismatic stroke making the reach (the IK course's RP; the RPR study's
// RPR, redundant for the tip point). A spatial arm with fewer than six joints cannot follow a
// general pose: it positions its tool point. (Catalogue: planar_3r "xyphi"; rp, rpr "xy"; prr,
// planar in the base xz plane, "position"; the 6- and 7-joint arms "pose".)
Task natural_task(const Chain& chain);

// A target for a task: pose -> a rigid frame; position -> (x, y, z); xy -> (x, y); xyphi -> (x, y, phi).
struct Target {
  Task task = Task::XY;
  Rigid pose;             // for Task::Pose
  Eigen::Vector3d value;  // for the others (unused entries zero)
};

// Error (target - current) in task coordinates, rows as task_rows(); the orientation error of a
// pose is the rotation vector of R_target R^T, the planar angle error is wrapped to (-pi, pi].
void task_error(const Target& target, const Rigid& current, double* err);

// The position and orientation parts of a task error (as task_error writes it) as the success
// tests read them: |translation rows| (overflow-safe) and |rotation vector| or |phi error|
// (0 for a task without orientation).
void task_error_norms(Task task, const double* err, double& error_p, double& error_r);

// Rotation vector (angle * axis, angle in [0, pi]) of a rotation matrix.
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R);

// The rows of the 6 x n geometric Jacobian that a task controls (task_rows(task) of them).
inline const int* task_row_indices(Task task) {
  static constexpr int kRows[4][6] = {{0, 1, 2, 3, 4, 5}, {0, 1, 2}, {0, 1}, {0, 1, 5}};
  return kRows[static_cast<int>(task)];
}

// The planar angle of a frame about the base z axis.
inline double planar_angle(const Rigid& T) { return std::atan2(T.R(1, 0), T.R(0, 0)); }

}  // namespace robokin
