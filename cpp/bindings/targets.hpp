// Task targets from numpy, shared by the Reach, IK and servo bindings: one target, or a batch of
// them. A target whose shape does not fit the task but fits another says which task takes it.
#pragma once

#include "arrays.hpp"

#include "robokin/task.hpp"

#include <string>
#include <vector>

namespace robokin::bind {

// A target from its raw numbers: 16 row-major for a pose, task_rows(task) values otherwise.
inline Target target_from(Task task, const double* data) {
  Target t;
  t.task = task;
  if (task == Task::Pose) {
    t.pose = Rigid::from_matrix(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(data));
  } else {
    t.value.setZero();
    for (int i = 0; i < task_rows(task); ++i) t.value(i) = data[i];
  }
  return t;
}

// The shape of one target of `task` (of each row of a batch), and what such a target is called.
inline std::vector<py::ssize_t> target_shape(Task task) {
  if (task == Task::Pose) return {4, 4};
  return {task_rows(task)};
}

inline std::string target_noun(Task task, bool plural) {
  switch (task) {
    case Task::Pose: return plural ? "frames" : "frame";
    case Task::Position: return plural ? "positions (x, y, z)" : "position (x, y, z)";
    case Task::XY: return plural ? "points (x, y)" : "point (x, y)";
    case Task::XYPhi: return plural ? "planar poses (x, y, phi)" : "planar pose (x, y, phi)";
  }
  return "?";
}

// For a target that did not convert for `task` (one, or a batch whose first axis counts them,
// named `count`): when its shape (each row's, for a batch) is another task's, a ValueError saying
// which, e.g.
//   target (3,) is a position (x, y, z): pass task="position" (task 'pose' takes a (4, 4) frame)
//   targets (10, 2) are points (x, y): pass task="xy" (task 'pose' takes (N, 4, 4) frames)
// A (3,) target is a position or, for a planar arm, also a planar pose: both are named then.
// Returns (the caller re-raises its own error) when the shape fits the task, or no task.
inline void explain_target_shape(const Chain& chain, Task task, py::handle obj, const char* name,
                                 const char* count = nullptr) {
  const bool batch = count != nullptr;
  const py::array a = py::array::ensure(obj);  // its own dtype: only the shape is read (no cast, no warning)
  if (!a || a.ndim() < (batch ? 2 : 1)) return;
  const std::vector<py::ssize_t> shape(a.shape() + (batch ? 1 : 0), a.shape() + a.ndim());
  if (shape == target_shape(task)) return;
  std::string what, pass;
  for (Task t : {Task::Pose, Task::XYPhi, Task::Position, Task::XY}) {
    if (target_shape(t) != shape || (t == Task::XYPhi && !chain.planar())) continue;
    what += (what.empty() ? "" : " or ") + std::string(batch ? "" : "a ") + target_noun(t, batch);
    pass += (pass.empty() ? "" : " or ") + std::string("task=\"") + task_name(t) + "\"";
  }
  if (what.empty()) return;
  const std::vector<py::ssize_t> want = target_shape(task);
  std::string expected;
  if (batch) {
    expected = std::string("(") + count;
    for (py::ssize_t d : want) expected += ", " + std::to_string(d);
    expected += ") " + target_noun(task, true);
  } else {
    expected = "a " + shape_of(static_cast<py::ssize_t>(want.size()), want.data()) + " " + target_noun(task, false);
  }
  fail(std::string(name) + " " + shape_of(a) + (batch ? " are " : " is ") + what + ": pass " + pass + " (task '" +
       task_name(task) + "' takes " + expected + ")");
}

// One target: a (4, 4) rigid transform for "pose", a (rows,) vector otherwise.
inline Target one_target(const Chain& chain, Task task, py::handle obj, const char* name = "target") {
  try {
    if (task == Task::Pose) {
      const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = as_transform(obj, name);
      return target_from(task, m.data());
    }
    const Eigen::VectorXd v = as_vector(obj, name, task_rows(task));
    return target_from(task, v.data());
  } catch (const py::value_error&) {
    explain_target_shape(chain, task, obj, name);
    throw;
  }
}

// A batch: (K, 4, 4) rigid transforms for "pose", (K, rows) otherwise, all finite.
inline std::vector<Target> many_targets(const Chain& chain, Task task, py::handle obj, const char* name,
                                        const char* count = "K") {
  Array a = as_array(obj, name);
  const int rows = task_rows(task);
  const bool ok = task == Task::Pose ? (a.ndim() == 3 && a.shape(1) == 4 && a.shape(2) == 4)
                                     : (a.ndim() == 2 && a.shape(1) == rows);
  if (!ok) {
    explain_target_shape(chain, task, a, name, count);
    fail(std::string(name) + ": expected shape (" + count + (task == Task::Pose ? ", 4, 4)" : ", " + std::to_string(rows) + ")") +
         " for task '" + task_name(task) + "', got " + shape_of(a));
  }
  require_finite(a.data(), a.size(), name);
  const long n = a.shape(0), stride = task == Task::Pose ? 16 : rows;
  std::vector<Target> targets;
  targets.reserve(n);
  for (long k = 0; k < n; ++k) {
    if (task == Task::Pose) rigid_at(a.data() + 16 * k, name, k);
    targets.push_back(target_from(task, a.data() + k * stride));
  }
  return targets;
}

}  // namespace robokin::bind
