// robokin.closed is bound in two files: ik_closed.cpp (IKSolutions and the free functions) and
// closed_solver.cpp (ClosedSolver). What they share.
#pragma once

#include "arrays.hpp"
#include "progress.hpp"

#include "robokin/ik_closed.hpp"

#include <vector>

namespace robokin::bind {

// (N, 4, 4) rigid frames; ValueError naming `name` for a wrong shape, a non-finite value or a frame
// that is not a rigid transform.
std::vector<Rigid> rigid_frames(ArrayLike targets, const char* name);

// A 6R closed form's batch on (N, 4, 4) frames, the GIL released: (q (N, 8, dof), singular (N,),
// within_limits (N, 8)); dof is 7 when a seventh joint is held. batch(targets, count, q,
// within_limits, singular, progress) runs the core's batch (ik_ur_batch, closed_solve_batch) for
// its arm; `what` names it in progress reports.
template <class Batch>
pybind11::tuple closed_batch_py(ArrayLike targets_obj, const char* what, const Batch& batch, int dof = 6) {
  namespace py = pybind11;
  const std::vector<Rigid> targets = rigid_frames(targets_obj, "targets");
  const long count = static_cast<long>(targets.size());
  py::array_t<double> q = new_array({static_cast<py::ssize_t>(count), 8, static_cast<py::ssize_t>(dof)});
  py::array_t<bool> within = new_array<bool>({count, 8}), singular = new_array<bool>({count});
  double* qd = q.mutable_data();
  bool* wd = within.mutable_data();
  bool* sd = singular.mutable_data();
  released(what, [&](Progress* progress) { batch(targets.data(), count, qd, wd, sd, progress); });
  return py::make_tuple(q, singular, within);
}

}  // namespace robokin::bind
