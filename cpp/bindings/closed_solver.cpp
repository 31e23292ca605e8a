// robokin.closed.ClosedSolver (the core's, closed_solver.hpp), closed_family and closed_solve: the
// closed form of an arm read from its chain's geometry.
#include "bindings.hpp"
#include "chain_args.hpp"
#include "closed_parts.hpp"
#include "options.hpp"
#include "progress.hpp"

#include "robokin/closed_solver.hpp"

#include <pybind11/typing.h>

#include <optional>
#include <string>
#include <utility>

namespace robokin::bind {
namespace {

// A held joint: None, or {index: value} with one int index (0-based, as in q) and a real value; a
// TypeError for another kind. What the values must be (7 joints, the index in range, the value
// finite, within the limits) is the core's check (joint_axes, ClosedSolver).
std::optional<HeldJoint> held_arg(py::handle obj) {
  if (obj.is_none()) return std::nullopt;
  if (!py::isinstance<py::dict>(obj)) fail_kind("locked: expected None or a dict {joint index: value}");
  const py::dict d = py::reinterpret_borrow<py::dict>(obj);
  if (d.size() != 1) fail("locked: expected one joint {index: value}, got " + std::to_string(d.size()));
  const auto item = *d.begin();
  const py::handle key = item.first, value = item.second;
  if (!PyIndex_Check(key.ptr()) || py::isinstance<py::bool_>(key))
    fail_kind("locked: the key must be a joint index (int), got " + py::repr(key).cast<std::string>());
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || !PyNumber_Check(value.ptr()) ||
      PyComplex_Check(value.ptr()))
    fail_kind("locked: the held value must be a real number, got " + py::repr(value).cast<std::string>());
  return HeldJoint{PyNumber_AsSsize_t(key.ptr(), nullptr), value.attr("__float__")().cast<double>()};
}

// The core's solver with the Python Chain it reads, kept alive (also in a solver unpickled with
// its chain).
struct BoundSolver {
  py::object owner;
  ClosedSolver solver;

  const Chain& chain() const { return owner.cast<const Chain&>(); }
  py::object limits() const {
    const JointLimits& l = solver.limits();
    return l.lower.size() ? py::object(py::make_tuple(to_numpy(l.lower), to_numpy(l.upper))) : py::object(py::none());
  }
  // None, or a new {index: value} of the held joint (a new dict: the solver's state is not a
  // caller's to change).
  py::object locked() const {
    if (!solver.held()) return py::none();
    py::dict d;
    d[py::int_(solver.held()->joint)] = py::float_(solver.held()->value);
    return d;
  }
  ClosedFormSolutions solve(ArrayLike target) const {
    return solver.solve(Rigid::from_matrix(as_transform(target, "target")));
  }
  py::tuple solve_batch(ArrayLike targets_obj) const {
    return closed_batch_py(targets_obj, "closed form", [&](const Rigid* targets, long count, double* q, bool* within,
                                                           bool* singular, Progress* progress) {
      solver.solve_batch(targets, count, q, within, singular, progress);
    }, chain().dof());  // 6, or 7 with one held
  }
};

// The solver of the chain (a Python Chain), or none when find finds no closed form.
std::unique_ptr<BoundSolver> bound_solver(py::object chain_obj, py::handle limits_obj, py::handle locked,
                                          const ClosedFamilyOptions& o, bool required) {
  const Chain& chain = chain_obj.cast<const Chain&>();
  JointLimits limits = limits_or_default(chain, limits_obj, chain.dof());
  const std::optional<HeldJoint> held = held_arg(locked);
  if (required) return std::make_unique<BoundSolver>(BoundSolver{chain_obj, ClosedSolver(chain, limits, o, held)});
  std::optional<ClosedSolver> found = ClosedSolver::find(chain, limits, o, held);
  return found ? std::make_unique<BoundSolver>(BoundSolver{chain_obj, std::move(*found)}) : nullptr;
}

std::unique_ptr<BoundSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 5, "ClosedSolver");  // (version, chain, limits, options, locked)
  if (!py::isinstance<Chain>(t[1])) fail("ClosedSolver state: expected a Chain");
  const ClosedFamilyOptions o = t[3].cast<ClosedFamilyOptions>();
  o.validate();
  return bound_solver(py::reinterpret_borrow<py::object>(t[1]), t[2], t[4], o, true);
}

// closed_family's answer as a tuple for robokin.closed.Family: (name, solvable, reason, meet,
// parallel, tol_distance).
py::tuple family_of(const Chain& chain, LockedLike locked, const py::kwargs& kwargs) {
  const ClosedFamilyOptions o = options_arg<ClosedFamilyOptions>(kwargs);
  const ClosedFamily f = closed_family(joint_axes(chain, held_arg(locked)), o);
  return py::make_tuple(f.name, f.kind != FamilyKind::None, f.reason, py::tuple(py::cast(f.meet)),
                        py::tuple(py::cast(f.parallel)), f.tol_distance);
}

void bind_solver_class(py::module_& m) {
  py::class_<BoundSolver> cls(
      m, "ClosedSolver",
      "The closed-form inverse kinematics of one arm, read from its chain once: solve(T) costs only the\n"
      "solve. Nothing changes during a call: one solver may be shared by every thread; it pickles\n"
      "with its chain, limits and options.");
  static const std::string init_doc = kwargs_doc<ClosedFamilyOptions>(
      "ClosedSolver(chain, limits='default', locked=None, *",
      "The closed form of chain, read from its joint axes at q = 0 whatever describes it: the UR\n"
      "closed form (robokin.closed.ur's) for the UR layout, the PUMA's (robokin.closed.puma560's) for\n"
      "a spherical wrist in the ortho-parallel layout (KUKA KR, ABB IRB, Fanuc; a shoulder offset\n"
      "allowed), each in vectorised stages; else the subproblems' for any arm robokin.closed.family\n"
      "recognises (ValueError saying why otherwise); the same solutions and labels. limits: 'default'\n"
      "for the chain's, None for none, or (lower, upper): for within_limits. locked: None, or\n"
      "{index: value} for a 7-joint chain, the joint (0-based, as in q) held at that value (within\n"
      "limits) and the 6 others solved, as robokin.closed.solve: the value decides the family, so\n"
      "a solver holds one value (a sweep makes one per value, or calls robokin.closed.solve).");
  cls.def(py::init([](const Chain& chain, ChainLimitsLike limits, LockedLike locked, const py::kwargs& kwargs) {
            return bound_solver(py::cast(chain, py::return_value_policy::reference), limits, locked,
                                options_arg<ClosedFamilyOptions>(kwargs), true);
          }),
          py::arg("chain"), py::arg("limits") = "default", py::arg("locked") = py::none(), init_doc.c_str())
      .def_static("find", [](const Chain& chain, ChainLimitsLike limits, LockedLike locked,
                             const py::kwargs& kwargs) -> py::typing::Optional<BoundSolver> {
            auto found = bound_solver(py::cast(chain, py::return_value_policy::reference), limits, locked,
                                      options_arg<ClosedFamilyOptions>(kwargs), false);
            return found ? py::cast(std::move(found)) : py::none();
          },
          py::arg("chain"), py::arg("limits") = "default", py::arg("locked") = py::none(),
          "The solver, or None when the arm has no closed form; options as keywords. Use ClosedSolver.find.")
      .def("solve", &BoundSolver::solve, py::arg("target"),
           "Every solution of the tool frame target (4, 4) -> IKSolutions, as robokin.closed.solve.")
      .def("solve_batch", &BoundSolver::solve_batch, py::arg("targets"),
           "solve for targets, (N, 4, 4) frames, on every core, the GIL released -> (q (N, 8, dof), singular (N,),\n"
           "within_limits (N, 8)), slots as robokin.closed.ur_batch's (UR_POSTURES); dof is 7 with a\n"
           "held joint (its value in its place), else 6.")
      .def_property_readonly("chain", [](const BoundSolver& s) { return s.owner; }, "The chain solved for.")
      .def_property_readonly("limits", &BoundSolver::limits,
                             "None or (lower, upper): the limits within_limits is measured against.")
      .def_property_readonly("family", [](const BoundSolver& s) { return s.solver.family(); },
                             "The decomposition solved (robokin.closed.family's name).")
      .def_property_readonly("locked", &BoundSolver::locked, "None, or {index: value}: the joint held.")
      .def(py::pickle(
          [](const BoundSolver& s) {
            return py::make_tuple(kStateVersion, s.owner, s.limits(), s.solver.options(), s.locked());
          },
          &solver_from_state))
      .def("__repr__", [](py::handle self) { return printed("closed_solver_repr", self); });
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
