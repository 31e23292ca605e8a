// Velocity-level IK: rk.resolved_rate and rk.servo (wrapped in python/robokin/resolved_rate.py).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"
#include "targets.hpp"

#include "robokin/reach.hpp"
#include "robokin/resolved_rate.hpp"

namespace robokin::bind {
namespace {

py::array_t<double> resolved_rate(const Chain& chain, ArrayLike q_obj, ArrayLike twist_obj, NullspaceLike nullspace,
                                  const py::kwargs& kwargs) {
  const RateOptions o = options_with_nullspace<RateOptions>(chain, kwargs, nullspace);
  const Vector q = as_vector(q_obj, "q", chain.dof());
  const Vector twist = as_vector(twist_obj, "twist", task_rows(o.task_for(chain)));
  RateController rate(chain, o);
  Eigen::VectorXd qdot(chain.dof());
  rate.joint_velocity(q.data(), twist.data(), qdot.data());
  if (!qdot.allFinite()) fail("twist: the joint velocities are not finite (twist or q too large)");
  return to_numpy(qdot);
}

ServoResult servo(const Chain& chain, ArrayLike poses, ArrayLike q0_obj, double dt, NullspaceLike nullspace,
                  const py::kwargs& kwargs) {
  const ServoOptions o = options_with_nullspace<ServoOptions>(chain, kwargs, nullspace);
  const std::vector<Target> targets = many_targets(chain, o.task_for(chain), poses, "poses");
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  RateController rate(chain, o);
  const ServoResult r = released("servo", [&](Progress* progress) {
    return rate.servo(o, dt, targets.data(), static_cast<long>(targets.size()), q0, progress);
  });
  if (!r.error_p.allFinite() || !r.error_r.allFinite())
    fail("poses: the tracking error is not finite (poses too far away)");
  return r;
}

}  // namespace

void bind_resolved_rate(py::module_& m) {
  OptionsClass<RateOptions>(m, "RateOptions", "The options of resolved-rate control (robokin.resolved_rate's keywords).")
      .fields();
  OptionsClass<ServoOptions>(m, "ServoOptions", "The options of the servo loop (robokin.servo's keywords).").fields();
  ResultClass<ServoResult>(m, "ServoResult", "What the servo loop did, one row per control step.", true).fields().done();
  m.def("resolved_rate", &resolved_rate, py::arg("chain"), py::arg("q"), py::arg("twist"), py::kw_only(),
        py::arg("nullspace") = py::none(),
        "Joint velocities for a task twist; options as keywords (RateOptions). Use robokin.resolved_rate.");
  m.def("servo", &servo, py::arg("chain"), py::arg("poses"), py::arg("q0"), py::arg("dt"), py::kw_only(),
        py::arg("nullspace") = py::none(),
        "Resolved-rate servo along targets; options as keywords (ServoOptions). Use robokin.servo.");
}

}  // namespace robokin::bind
