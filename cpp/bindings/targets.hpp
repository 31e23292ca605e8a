// Task targets from numpy, shared by the Reach and IK bindings: one target, or a batch of them.
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

// One target: a (4, 4) rigid transform for "pose", a (rows,) vector otherwise.
inline Target one_target(Task task, py::handle obj, const char* name = "target") {
  if (task == Task::Pose) {
    const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = as_transform(obj, name);
    return target_from(task, m.data());
  }
  const Eigen::VectorXd v = as_vector(obj, name, task_rows(task));
  return target_from(task, v.data());
}

// A batch: (K, 4, 4) rigid transforms for "pose", (K, rows) otherwise, all finite.
inline std::vector<Target> many_targets(Task task, py::handle obj, const char* name, const char* count = "K") {
  Array a = as_array(obj, name);
  const int rows = task_rows(task);
  const bool ok = task == Task::Pose ? (a.ndim() == 3 && a.shape(1) == 4 && a.shape(2) == 4)
                                     : (a.ndim() == 2 && a.shape(1) == rows);
  if (!ok)
    fail(std::string(name) + ": expected shape (" + count + (task == Task::Pose ? ", 4, 4)" : ", " + std::to_string(rows) + ")") +
         " for task '" + task_name(task) + "', got " + shape_of(a));
  require_finite(a.data(), a.size(), name);
  const long n = a.shape(0), stride = task == Task::Pose ? 16 : rows;
  std::vector<Target> targets;
  targets.reserve(n);
  for (long k = 0; k < n; ++k) {
    if (task == Task::Pose) as_transform(py::array_t<double>({4, 4}, a.data() + 16 * k), name);
    targets.push_back(target_from(task, a.data() + k * stride));
  }
  return targets;
}

}  // namespace robokin::bind
