// robokin.closed.ClosedSolver: a closed form bound to a chain and its limits, read once. It holds no
// state that a call changes: one solver may serve every thread at once.
#include "bindings.hpp"
#include "chain_args.hpp"
#include "closed_parts.hpp"

#include "robokin/ik_closed.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace robokin::bind {
namespace {

// The chain's UR geometry, a ValueError naming the argument (chain) when it has not the UR layout.
URArm arm_of(const Chain& chain) {
  try {
    return ur_arm(chain);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    fail("chain: " + (what.rfind("robot: ", 0) == 0 ? what.substr(7) : what));
  }
}

struct ClosedSolver {
  py::object owner;  // the Python Chain, kept alive (also in a solver unpickled with its chain)
  const Chain* chain;
  py::object limits_state;  // None or (lower, upper) as resolved: what pickling keeps
  JointLimits limits;
  URArm arm;

  ClosedSolver(py::object c, py::handle limits_obj)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()),
        limits(limits_or_default(*chain, limits_obj, chain->dof())), arm(arm_of(*chain)) {
    limits_state = limits.lower.size() ? py::object(py::make_tuple(to_numpy(limits.lower), to_numpy(limits.upper)))
                                       : py::object(py::none());
  }

  ClosedFormSolutions solve(ArrayLike target) const {
    return ik_ur(arm, *chain, Rigid::from_matrix(as_transform(target, "target")), limits);
  }
  py::tuple solve_batch(ArrayLike targets) const { return ur_batch_with(targets, *chain, arm, limits); }
};

std::unique_ptr<ClosedSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 3, "ClosedSolver");  // (version, chain, limits)
  if (!py::isinstance<Chain>(t[1])) fail("ClosedSolver state: expected a Chain");
  return std::make_unique<ClosedSolver>(py::reinterpret_borrow<py::object>(t[1]), t[2]);
}

}  // namespace

void bind_closed_solver(py::module_& m) {
  py::class_<ClosedSolver>(
      m, "ClosedSolver",
      "The closed-form inverse kinematics of one arm, read from its chain once: solve(T) costs only the\n"
      "solve. Nothing changes during a call: one solver may be shared by every thread; it pickles\n"
      "with its chain and limits.")
      .def(py::init([](const Chain& chain, ChainLimitsLike limits) {
             return std::make_unique<ClosedSolver>(py::cast(chain, py::return_value_policy::reference), limits);
           }),
           py::arg("chain"), py::arg("limits") = "default", py::keep_alive<1, 2>(),
           "The closed form of chain (a UR-family arm: three parallel axes 2, 3, 4, as\n"
           "robokin.closed.ur reads it; ValueError otherwise). limits: 'default' for the chain's,\n"
           "None for none, or (lower, upper): for within_limits (every solution is returned).")
      .def("solve", &ClosedSolver::solve, py::arg("target"),
           "Every solution of the tool frame target (4, 4) -> IKSolutions, as robokin.closed.ur.")
      .def("solve_batch", &ClosedSolver::solve_batch, py::arg("targets"),
           "solve for (N, 4, 4) frames on every core, the GIL released -> (q (N, 8, 6), singular (N,),\n"
           "within_limits (N, 8)), as robokin.closed.ur_batch.")
      .def_property_readonly("chain", [](const ClosedSolver& s) { return s.owner; }, "The chain solved for.")
      .def_property_readonly("limits", [](const ClosedSolver& s) { return s.limits_state; },
                             "None or (lower, upper): the limits within_limits is measured against.")
      .def(py::pickle([](const ClosedSolver& s) { return py::make_tuple(kStateVersion, s.owner, s.limits_state); },
                      &solver_from_state))
      .def("__repr__", [](const ClosedSolver& s) {
        return "ClosedSolver(" + py::repr(s.owner).cast<std::string>() +
               (s.limits_state.is_none() ? ", limits=None)" : ")");
      });
}

}  // namespace robokin::bind
