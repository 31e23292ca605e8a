// Velocity-level IK: rk.resolved_rate and rk.servo (wrapped in python/robokin/resolved_rate.py).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "progress.hpp"
#include "targets.hpp"

#include "robokin/reach.hpp"
#include "robokin/resolved_rate.hpp"

#include <string>

namespace robokin::bind {
namespace {

RateOptions rate_options(const Chain& chain, TaskName task, double damping, NullspaceLike nullspace) {
  RateOptions o;
  o.task = task_of(task, chain);
  o.damping = damping;
  o.nullspace_gains = nullspace_gains(chain, nullspace);
  check_rate_options(chain, o);
  return o;
}

py::array_t<double> resolved_rate(const Chain& chain, ArrayLike q_obj, ArrayLike twist_obj, double damping,
                                  NullspaceLike nullspace, TaskName task) {
  const RateOptions o = rate_options(chain, task, damping, nullspace);
  const Vector q = as_vector(q_obj, "q", chain.dof());
  const Vector twist = as_vector(twist_obj, "twist", task_rows(o.task));
  RateController rate(chain, o);
  Eigen::VectorXd qdot(chain.dof());
  rate.joint_velocity(q.data(), twist.data(), qdot.data());
  if (!qdot.allFinite()) fail("twist: the joint velocities are not finite (twist or q too large)");
  return to_numpy(qdot);
}

py::tuple servo(const Chain& chain, ArrayLike poses, ArrayLike q0_obj, double dt, double gain, double damping,
                NullspaceLike nullspace, TaskName task, bool saturate) {
  ServoOptions o;
  o.rate = rate_options(chain, task, damping, nullspace);
  o.dt = dt;
  o.gain = gain;
  o.saturate = saturate;
  check_servo_options(chain, o);
  const std::vector<Target> targets = many_targets(chain, o.rate.task, poses, "poses");
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  const auto count = static_cast<py::ssize_t>(targets.size()), n = static_cast<py::ssize_t>(chain.dof());
  py::array_t<double> q({count, n}), qdot({count, n}), ep(count), er(count);
  RateController rate(chain, o.rate);
  PythonProgress progress("servo");
  {
    py::gil_scoped_release release;
    rate.servo(o, targets.data(), count, q0, q.mutable_data(), qdot.mutable_data(), ep.mutable_data(),
               er.mutable_data(), &progress);
  }
  if (!all_finite(ep.data(), count) || !all_finite(er.data(), count))
    fail("poses: the tracking error is not finite (poses too far away)");
  return py::make_tuple(q, qdot, ep, er);
}

}  // namespace

void bind_resolved_rate(py::module_& m) {
  m.def("resolved_rate", &resolved_rate, py::arg("chain"), py::arg("q"), py::arg("twist"), py::arg("damping") = 0.0,
        py::arg("nullspace") = py::none(), py::arg("task") = py::none(),
        "Joint velocities for a task twist (damped least squares + null-space term). Use robokin.resolved_rate.");
  m.def("servo", &servo, py::arg("chain"), py::arg("poses"), py::arg("q0"), py::arg("dt"), py::arg("gain") = 0.75,
        py::arg("damping") = 0.0, py::arg("nullspace") = py::none(), py::arg("task") = py::none(),
        py::arg("saturate") = true, "Resolved-rate servo along targets: (q, qdot, error_p, error_r). Use robokin.servo.");
}

}  // namespace robokin::bind
