// robokin.closed.ClosedSolver, closed_family and closed_solve: the closed form of an arm read from
// its chain's geometry. A solver holds no state that a call changes: one may serve every thread.
#include "bindings.hpp"
#include "chain_args.hpp"
#include "closed_parts.hpp"
#include "options.hpp"
#include "progress.hpp"

#include "robokin/closed_solve.hpp"
#include "robokin/ik_closed.hpp"

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace robokin::bind {
namespace {

ClosedFamilyOptions family_options(const py::kwargs& kwargs) {
  const ClosedFamilyOptions o = OptionsClass<ClosedFamilyOptions>::from_kwargs(kwargs);
  o.validate();
  return o;
}

// The UR geometry when the chain has the UR layout (its own closed form, ik_ur), else none.
std::optional<URArm> ur_layout(const Chain& chain) {
  try {
    return ur_arm(chain);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

ClosedArm closed_arm_arg(const Chain& chain, const ClosedFamilyOptions& o) {
  try {
    return closed_arm(chain, o);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
}

struct ClosedSolver {
  py::object owner;  // the Python Chain, kept alive (also in a solver unpickled with its chain)
  const Chain* chain;
  ClosedFamilyOptions options;
  py::object limits_state;  // None or (lower, upper) as resolved: what pickling keeps
  JointLimits limits;
  std::optional<URArm> ur;  // the UR layout of a DH table: robokin.closed.ur's closed form
  ClosedArm arm;            // otherwise the subproblems' (closed_solve.hpp)

  ClosedSolver(py::object c, py::handle limits_obj, const ClosedFamilyOptions& o)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()), options(o),
        limits(limits_or_default(*chain, limits_obj, chain->dof())), ur(ur_layout(*chain)) {
    if (!ur) arm = closed_arm_arg(*chain, options);
    limits_state = limits.lower.size() ? py::object(py::make_tuple(to_numpy(limits.lower), to_numpy(limits.upper)))
                                       : py::object(py::none());
  }

  ClosedFormSolutions solve(const Rigid& T) const {
    return ur ? ik_ur(*ur, *chain, T, limits) : closed_solve(arm, *chain, T, limits);
  }
  ClosedFormSolutions solve_py(ArrayLike target) const {
    return solve(Rigid::from_matrix(as_transform(target, "target")));
  }
  py::tuple solve_batch(ArrayLike targets) const;
  std::string family() const { return ur ? "three parallel axes 2, 3, 4" : arm.family.name; }
};

py::tuple ClosedSolver::solve_batch(ArrayLike targets_obj) const {
  if (ur) return ur_batch_with(targets_obj, *chain, *ur, limits);
  return closed_batch_py(targets_obj, "closed form", [&](const Rigid* targets, long count, double* q, bool* within,
                                                         bool* singular, Progress* progress) {
    closed_solve_batch(arm, *chain, targets, count, limits, q, within, singular, progress);
  });
}

std::unique_ptr<ClosedSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 4, "ClosedSolver");  // (version, chain, limits, options)
  if (!py::isinstance<Chain>(t[1])) fail("ClosedSolver state: expected a Chain");
  const ClosedFamilyOptions o = t[3].cast<ClosedFamilyOptions>();
  o.validate();
  return std::make_unique<ClosedSolver>(py::reinterpret_borrow<py::object>(t[1]), t[2], o);
}

// closed_family's answer as a tuple for robokin.closed.Family: (name, solvable, reason, meet,
// parallel, tol_distance).
py::tuple family_of(const Chain& chain, const py::kwargs& kwargs) {
  const ClosedFamily f = closed_family(chain, family_options(kwargs));
  return py::make_tuple(f.name, f.kind != FamilyKind::None, f.reason, py::tuple(py::cast(f.meet)),
                        py::tuple(py::cast(f.parallel)), f.tol_distance);
}

void bind_solver_class(py::module_& m) {
  py::class_<ClosedSolver> cls(
      m, "ClosedSolver",
      "The closed-form inverse kinematics of one arm, read from its chain once: solve(T) costs only the\n"
      "solve. Nothing changes during a call: one solver may be shared by every thread; it pickles\n"
      "with its chain, limits and options.");
  static const std::string init_doc = kwargs_doc<ClosedFamilyOptions>(
      "ClosedSolver(chain, limits='default', *",
      "The closed form of chain: robokin.closed.ur's for a UR table, else the subproblems' for any\n"
      "arm robokin.closed.family recognises (ValueError saying why otherwise). limits: 'default'\n"
      "for the chain's, None for none, or (lower, upper): for within_limits.");
  cls.def(py::init([](const Chain& chain, ChainLimitsLike limits, const py::kwargs& kwargs) {
            return std::make_unique<ClosedSolver>(py::cast(chain, py::return_value_policy::reference), limits,
                                                  family_options(kwargs));
          }),
          py::arg("chain"), py::arg("limits") = "default", py::keep_alive<1, 2>(), init_doc.c_str())
      .def("solve", &ClosedSolver::solve_py, py::arg("target"),
           "Every solution of the tool frame target (4, 4) -> IKSolutions, as robokin.closed.solve.")
      .def("solve_batch", &ClosedSolver::solve_batch, py::arg("targets"),
           "solve for (N, 4, 4) frames on every core, the GIL released -> (q (N, 8, 6), singular (N,),\n"
           "within_limits (N, 8)), slots as robokin.closed.ur_batch's (UR_POSTURES).")
      .def_property_readonly("chain", [](const ClosedSolver& s) { return s.owner; }, "The chain solved for.")
      .def_property_readonly("limits", [](const ClosedSolver& s) { return s.limits_state; },
                             "None or (lower, upper): the limits within_limits is measured against.")
      .def_property_readonly("family", &ClosedSolver::family, "The decomposition solved (robokin.closed.family's name).")
      .def(py::pickle(
          [](const ClosedSolver& s) { return py::make_tuple(kStateVersion, s.owner, s.limits_state, s.options); },
          &solver_from_state))
      .def("__repr__", [](const ClosedSolver& s) {
        return "ClosedSolver(" + py::repr(s.owner).cast<std::string>() + ", family='" + s.family() + "'" +
               (s.limits_state.is_none() ? ", limits=None)" : ")");
      });
}

}  // namespace

void bind_closed_solver(py::module_& m) {
  OptionsClass<ClosedFamilyOptions>(m, "ClosedFamilyOptions",
                                    "The options of robokin.closed.family, solve and ClosedSolver (keywords).")
      .fields();
  bind_solver_class(m);
  static const std::string family_doc = kwargs_doc<ClosedFamilyOptions>(
      "closed_family(chain, *", "The chain's decomposition: (name, solvable, reason, meet, parallel, tol_distance).");
  m.def("closed_family", &family_of, py::arg("chain"), family_doc.c_str());
}

}  // namespace robokin::bind
