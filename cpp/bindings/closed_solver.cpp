// robokin.closed.ClosedSolver, closed_family and closed_solve: the closed form of an arm read from
// its chain's geometry. A solver holds no state that a call changes: one may serve every thread.
#include "bindings.hpp"
#include "chain_args.hpp"
#include "closed_parts.hpp"
#include "options.hpp"
#include "progress.hpp"

#include "robokin/closed_solve.hpp"
#include "robokin/ik_closed.hpp"

#include <cmath>
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

ClosedArm closed_arm_arg(const Chain& chain, const ClosedFamilyOptions& o, int held, double value) {
  try {
    return closed_arm(chain, o, held, value);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
}

// A held joint: None, or {index: value} with one int index (0-based, as in q) and a real value.
// TypeError for another kind; ValueError for an index out of range, a value that is not finite or
// outside `limits` (when there are limits). The chain's own checks (7 joints) are closed_arm's.
std::pair<int, double> held_arg(const Chain& chain, py::handle obj, const JointLimits& limits) {
  if (obj.is_none()) return {-1, 0.0};
  if (!py::isinstance<py::dict>(obj)) fail_kind("locked: expected None or a dict {joint index: value}");
  const py::dict d = py::reinterpret_borrow<py::dict>(obj);
  if (d.size() != 1) fail("locked: expected one joint {index: value}, got " + std::to_string(d.size()));
  const auto item = *d.begin();
  const py::handle key = item.first, value = item.second;
  const bool integer = py::isinstance<py::int_>(key) || py::hasattr(key, "__index__");
  if (!integer || py::isinstance<py::bool_>(key) || py::isinstance<py::float_>(key))
    fail_kind("locked: the key must be a joint index (int), got " + py::repr(key).cast<std::string>());
  const long index = key.attr("__index__")().cast<long>();
  if (index < 0 || index >= chain.dof())
    fail("locked: joint index " + std::to_string(index) + " out of range for a chain of " +
         std::to_string(chain.dof()) + " joints (0 to " + std::to_string(chain.dof() - 1) + ")");
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
                                            py::hasattr(value, "__float__")) || py::isinstance<py::str>(value))
    fail_kind("locked: the held value must be a real number, got " + py::repr(value).cast<std::string>());
  const double v = value.attr("__float__")().cast<double>();
  if (!std::isfinite(v)) fail("locked: the held value must be finite, got " + py::repr(value).cast<std::string>());
  if (limits.lower.size() == chain.dof() && !(v >= limits.lower[index] && v <= limits.upper[index]))
    fail("locked: q[" + std::to_string(index) + "] = " + py::repr(py::float_(v)).cast<std::string>() +
         " is outside the joint's limits [" + py::repr(py::float_(limits.lower[index])).cast<std::string>() + ", " +
         py::repr(py::float_(limits.upper[index])).cast<std::string>() + "]");
  return {static_cast<int>(index), v};
}

struct ClosedSolver {
  py::object owner;  // the Python Chain, kept alive (also in a solver unpickled with its chain)
  const Chain* chain;
  ClosedFamilyOptions options;
  py::object limits_state;  // None or (lower, upper) as resolved: what pickling keeps
  JointLimits limits;
  std::optional<URArm> ur;  // the UR layout of a DH table: robokin.closed.ur's closed form
  ClosedArm arm;            // otherwise the subproblems' (closed_solve.hpp)

  ClosedSolver(py::object c, py::handle limits_obj, py::handle locked, const ClosedFamilyOptions& o)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()), options(o),
        limits(limits_or_default(*chain, limits_obj, chain->dof())) {
    const auto [held, value] = held_arg(*chain, locked, limits);
    if (held < 0) ur = ur_layout(*chain);
    if (!ur) arm = closed_arm_arg(*chain, options, held, value);
    limits_state = limits.lower.size() ? py::object(py::make_tuple(to_numpy(limits.lower), to_numpy(limits.upper)))
                                       : py::object(py::none());
  }

  // None, or a new {index: value} of the held joint (a new dict: the solver's state is not a
  // caller's to change).
  py::object locked() const {
    if (arm.held < 0) return py::none();
    py::dict d;
    d[py::int_(arm.held)] = py::float_(arm.held_value);
    return d;
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
  }, chain->dof());  // 6, or 7 with one held (closed_arm refuses any other)
}

std::unique_ptr<ClosedSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 5, "ClosedSolver");  // (version, chain, limits, options, locked)
  if (!py::isinstance<Chain>(t[1])) fail("ClosedSolver state: expected a Chain");
  const ClosedFamilyOptions o = t[3].cast<ClosedFamilyOptions>();
  o.validate();
  return std::make_unique<ClosedSolver>(py::reinterpret_borrow<py::object>(t[1]), t[2], t[4], o);
}

// closed_family's answer as a tuple for robokin.closed.Family: (name, solvable, reason, meet,
// parallel, tol_distance).
py::tuple family_of(const Chain& chain, LockedLike locked, const py::kwargs& kwargs) {
  const ClosedFamilyOptions o = family_options(kwargs);
  const auto [held, value] = held_arg(chain, locked, JointLimits{});
  ClosedFamily f;
  try {
    f = closed_family(joint_axes(chain, held, value), o);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
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
      "ClosedSolver(chain, limits='default', locked=None, *",
      "The closed form of chain: robokin.closed.ur's for a UR table, else the subproblems' for any\n"
      "arm robokin.closed.family recognises (ValueError saying why otherwise). limits: 'default'\n"
      "for the chain's, None for none, or (lower, upper): for within_limits. locked: None, or\n"
      "{index: value} for a 7-joint chain, the joint (0-based, as in q) held at that value (within\n"
      "limits) and the 6 others solved, as robokin.closed.solve: the value decides the family, so\n"
      "a solver holds one value (a sweep makes one per value, or calls robokin.closed.solve).");
  cls.def(py::init([](const Chain& chain, ChainLimitsLike limits, LockedLike locked, const py::kwargs& kwargs) {
            return std::make_unique<ClosedSolver>(py::cast(chain, py::return_value_policy::reference), limits,
                                                  locked, family_options(kwargs));
          }),
          py::arg("chain"), py::arg("limits") = "default", py::arg("locked") = py::none(), py::keep_alive<1, 2>(),
          init_doc.c_str())
      .def("solve", &ClosedSolver::solve_py, py::arg("target"),
           "Every solution of the tool frame target (4, 4) -> IKSolutions, as robokin.closed.solve.")
      .def("solve_batch", &ClosedSolver::solve_batch, py::arg("targets"),
           "solve for (N, 4, 4) frames on every core, the GIL released -> (q (N, 8, dof), singular (N,),\n"
           "within_limits (N, 8)), slots as robokin.closed.ur_batch's (UR_POSTURES); dof is 7 with a\n"
           "held joint (its value in its place), else 6.")
      .def_property_readonly("chain", [](const ClosedSolver& s) { return s.owner; }, "The chain solved for.")
      .def_property_readonly("limits", [](const ClosedSolver& s) { return s.limits_state; },
                             "None or (lower, upper): the limits within_limits is measured against.")
      .def_property_readonly("family", &ClosedSolver::family, "The decomposition solved (robokin.closed.family's name).")
      .def_property_readonly("locked", &ClosedSolver::locked, "None, or {index: value}: the joint held.")
      .def(py::pickle(
          [](const ClosedSolver& s) {
            return py::make_tuple(kStateVersion, s.owner, s.limits_state, s.options, s.locked());
          },
          &solver_from_state))
      .def("__repr__", [](const ClosedSolver& s) {
        return "ClosedSolver(" + py::repr(s.owner).cast<std::string>() + ", family='" + s.family() + "'" +
               (s.limits_state.is_none() ? ", limits=None" : "") +
               (s.arm.held >= 0 ? ", locked=" + py::repr(s.locked()).cast<std::string>() : "") + ")";
      });
}

}  // namespace

void bind_closed_solver(py::module_& m) {
  OptionsClass<ClosedFamilyOptions>(m, "ClosedFamilyOptions",
                                    "The options of robokin.closed.family, solve and ClosedSolver (keywords).")
      .fields();
  bind_solver_class(m);
  static const std::string family_doc = kwargs_doc<ClosedFamilyOptions>(
      "closed_family(chain, locked=None, *",
      "The chain's decomposition (with a joint held: locked={index: value}): (name, solvable, reason,\n"
      "meet, parallel, tol_distance).");
  m.def("closed_family", &family_of, py::arg("chain"), py::arg("locked") = py::none(), family_doc.c_str());
}

}  // namespace robokin::bind
