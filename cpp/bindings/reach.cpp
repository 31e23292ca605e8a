// The Reach loop and path tracking (the RPR study, Algorithm 1).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"
#include "targets.hpp"

#include "robokin/reach.hpp"

#include <cmath>
#include <vector>

namespace robokin::bind {
namespace {

ReachResult reach(const Chain& chain, ArrayLike target, ArrayLike q_obj, TaskName task_obj, NullspaceLike nullspace,
                  const py::kwargs& kwargs) {
  const Task task = task_of(task_obj, chain);
  const Target t = one_target(chain, task, target);
  const Vector q = as_vector(q_obj, "q", chain.dof());
  Reacher reacher(chain, task, options_with_nullspace<ReachOptions>(chain, kwargs, nullspace));
  ReachResult r = reacher.reach(t, q);
  // Finite inputs near 1e308 can still give an error beyond the largest double: no inf returned.
  if (!std::isfinite(r.error)) fail("target: the task error is not finite (the target is too far away)");
  return r;
}

TrackResult track(const Chain& chain, ArrayLike points, ArrayLike q0_obj, TaskName task_obj, NullspaceLike nullspace,
                  const py::kwargs& kwargs) {
  const Task task = task_of(task_obj, chain);
  const std::vector<Target> targets = many_targets(chain, task, points, "points");
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  Reacher reacher(chain, task, options_with_nullspace<ReachOptions>(chain, kwargs, nullspace));
  const TrackResult r = released("track", [&](Progress* progress) {
    return reacher.track(targets.data(), static_cast<long>(targets.size()), q0, progress);
  });
  if (!r.error.allFinite()) fail("points: the task error is not finite (a point is too far away)");
  return r;
}

}  // namespace

void bind_reach(py::module_& m) {
  OptionsClass<ReachOptions>(m, "ReachOptions", "The options of one Reach (the RPR study, Algorithm 1); the seed's values by default.")
      .fields();
  ResultClass<ReachResult>(m, "ReachResult", "What one Reach call did.", false).fields().done();
  ResultClass<TrackResult>(m, "TrackResult", "What tracking a path did, one row per path point.", true).fields().done();
  m.def("reach", &reach, py::arg("chain"), py::arg("target"), py::arg("q"), py::arg("task") = py::none(), py::kw_only(),
        py::arg("nullspace") = py::none(),
        "One Reach call (the RPR study, Algorithm 1); options as keywords (ReachOptions). Use robokin.reach, which also warns.");
  m.def("track", &track, py::arg("chain"), py::arg("points"), py::arg("q0"), py::arg("task") = py::none(), py::kw_only(),
        py::arg("nullspace") = py::none(),
        "Reach every point of a path in turn; options as keywords (ReachOptions). Use robokin.track, which also warns.");
  m.def(
      "joint_limit_cost",
      [](const Chain& chain, ArrayLike q_obj) -> py::object {
        const QView q(q_obj);
        const long count = check_q(chain, q), n = chain.dof();
        py::array_t<double> out = new_array({count < 0 ? 1 : count});
        for (py::ssize_t k = 0; k < out.size(); ++k) out.mutable_data()[k] = joint_limit_cost(chain, q.data + k * n);
        // A finite q far outside the limits (near 1e300) squares to inf: say so rather than return it.
        if (!all_finite(out.data(), out.size())) fail("q: the cost is not finite (q is too far from the limits)");
        if (count < 0) return py::float_(out.data()[0]);
        return std::move(out);
      },
      py::arg("chain"), py::arg("q"),
      "Seed 000's joint-limit cost z = 1/2 |W (qbar - q)|^2 of the chain's limits, W = diag(1 /\n"
      "(q_max - q_min)) (0 for an unlimited joint), qbar their middle: a float for q (dof,), an\n"
      "array (N,) for a batch (N, dof).");
}

}  // namespace robokin::bind
