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

// A held joint: None, or {index: value} with one int index (0-based, as in q) and a real value; a
// TypeError for another kind. What the values must be (7 joints, the index in range, the value
// finite) is the core's check (joint_axes).
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

// The held value within the chain's limits (when there are limits).
void require_held_within(const std::optional<HeldJoint>& held, const JointLimits& limits) {
  if (!held || limits.lower.size() == 0) return;
  const auto text = [](double v) { return py::repr(py::float_(v)).cast<std::string>(); };
  const long i = held->joint;
  if (!(held->value >= limits.lower[i] && held->value <= limits.upper[i]))
    fail("locked: q[" + std::to_string(i) + "] = " + text(held->value) + " is outside the joint's limits [" +
         text(limits.lower[i]) + ", " + text(limits.upper[i]) + "]");
}

struct ClosedSolver {
  py::object owner;  // the Python Chain, kept alive (also in a solver unpickled with its chain)
  const Chain* chain;
  ClosedFamilyOptions options;
  py::object limits_state;  // None or (lower, upper) as resolved: what pickling keeps
  JointLimits limits;
  // The closed form of the arm's layout when it has one (ik_ur's, ik_spherical's: each solve in
  // vectorised stages), otherwise the subproblems' (closed_solve.hpp); the same solutions and labels.
  std::optional<URArm> ur;
  std::optional<SphericalArm> spherical;
  ClosedArm arm;

  ClosedSolver(py::object c, py::handle limits_obj, py::handle locked, const ClosedFamilyOptions& o)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()), options(o),
        limits(limits_or_default(*chain, limits_obj, chain->dof())) {
    const std::optional<HeldJoint> held = held_arg(locked);
    if (!held) ur = ur_layout(*chain);
    if (!held && !ur) spherical = spherical_layout(*chain);
    if (!ur && !spherical) arm = closed_arm(*chain, options, held);  // the core's ValueError says why not
    require_held_within(held, limits);
    limits_state = limits.lower.size() ? py::object(py::make_tuple(to_numpy(limits.lower), to_numpy(limits.upper)))
                                       : py::object(py::none());
  }

  // None, or a new {index: value} of the held joint (a new dict: the solver's state is not a
  // caller's to change).
  py::object locked() const {
    if (!arm.axes.held) return py::none();
    py::dict d;
    d[py::int_(arm.axes.held->joint)] = py::float_(arm.axes.held->value);
    return d;
  }

  ClosedFormSolutions solve(const Rigid& T) const {
    if (ur) return ik_ur(*ur, *chain, T, limits);
    return spherical ? ik_spherical(*spherical, *chain, T, limits) : closed_solve(arm, *chain, T, limits);
  }
  ClosedFormSolutions solve_py(ArrayLike target) const {
    return solve(Rigid::from_matrix(as_transform(target, "target")));
  }
  py::tuple solve_batch(ArrayLike targets) const;
  std::string family() const {
    return ur ? "three parallel axes 2, 3, 4" : spherical ? "spherical wrist, axes 2, 3 parallel" : arm.family.name;
  }
};

py::tuple ClosedSolver::solve_batch(ArrayLike targets_obj) const {
  if (ur) return ur_batch_with(targets_obj, *chain, *ur, limits);
  if (spherical)
    return closed_batch_py(targets_obj, "closed form", [&](const Rigid* targets, long count, double* q, bool* within,
                                                           bool* singular, Progress* progress) {
      ik_spherical_batch(*spherical, *chain, targets, count, limits, q, within, singular, progress);
    });
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
  const ClosedFamilyOptions o = options_arg<ClosedFamilyOptions>(kwargs);
  const ClosedFamily f = closed_family(joint_axes(chain, held_arg(locked)), o);
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
            return std::make_unique<ClosedSolver>(py::cast(chain, py::return_value_policy::reference), limits,
                                                  locked, options_arg<ClosedFamilyOptions>(kwargs));
          }),
          py::arg("chain"), py::arg("limits") = "default", py::arg("locked") = py::none(), py::keep_alive<1, 2>(),
          init_doc.c_str())
      .def("solve", &ClosedSolver::solve_py, py::arg("target"),
           "Every solution of the tool frame target (4, 4) -> IKSolutions, as robokin.closed.solve.")
      .def("solve_batch", &ClosedSolver::solve_batch, py::arg("targets"),
           "solve for targets, (N, 4, 4) frames, on every core, the GIL released -> (q (N, 8, dof), singular (N,),\n"
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
               (s.arm.axes.held ? ", locked=" + py::repr(s.locked()).cast<std::string>() : "") + ")";
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
