// robokin.closed: closed-form inverse kinematics, every solution labelled by posture: IKSolutions,
// the closed forms of the named arms (planar RP / 2R / 3R, anthropomorphic, spherical wrist and its
// path, UR), and ClosedSolver with closed_family: the closed form of an arm read from its chain's
// geometry (the core's closed_solver.hpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"

#include "robokin/closed_solver.hpp"
#include "robokin/ik_closed.hpp"

#include <pybind11/stl.h>
#include <pybind11/typing.h>

#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace robokin::bind {
namespace {

// (N, 4, 4) rigid frames; ValueError naming `name` for a wrong shape, a non-finite value or a frame
// that is not a rigid transform.
std::vector<Rigid> rigid_frames(ArrayLike targets_obj, const char* name) {
  const Array a = rows_arg(targets_obj, name, {4, 4}, "N");
  const long count = a.shape(0);
  std::vector<Rigid> targets(count);
  for (long k = 0; k < count; ++k) targets[k] = Rigid::from_matrix(rigid_at(a.data() + 16 * k, name, k));
  return targets;
}

ClosedFormSolutions planar_rp(ArrayLike target, LimitsLike limits) {
  const Vector p = as_vector(target, "target", 2);
  return ik_planar_rp(p(0), p(1), limits_arg(limits, 2, {false, true}));
}

ClosedFormSolutions planar_2r(ArrayLike target, double a1, double a2, LimitsLike limits) {
  const Vector p = as_vector(target, "target", 2);
  return ik_planar_2r(a1, a2, p(0), p(1), limits_arg(limits, 2));
}

ClosedFormSolutions planar_3r(ArrayLike target, double a1, double a2, double a3, const std::string& method,
                              LimitsLike limits) {
  const Vector p = as_vector(target, "target", 3);
  if (method != "algebraic" && method != "geometric")
    fail("method: expected 'algebraic' or 'geometric', got '" + method + "'");
  return ik_planar_3r(a1, a2, a3, p(0), p(1), p(2), method == "geometric", limits_arg(limits, 3));
}

// The arm's lengths, checked by the core (ArmGeometry::validate).
ArmGeometry arm_arg(double d1, double a2, double a3, double d3, double d4) {
  const ArmGeometry g{d1, a2, a3, d3, d4};
  g.validate();
  return g;
}

ClosedFormSolutions anthropomorphic(ArrayLike target, double a2, double a3, double d1, LimitsLike limits) {
  const Vector p = as_vector(target, "target", 3);
  return ik_anthropomorphic(arm_arg(d1, a2, a3, 0, 0), p, limits_arg(limits, 3));
}

ClosedFormSolutions spherical_wrist_6r(ArrayLike target, double a2, double a3, double d3, double d4, double d1,
                                       double d6, LimitsLike limits) {
  const Rigid T = Rigid::from_matrix(as_transform(target, "target"));
  return ik_spherical_wrist_6r(arm_arg(d1, a2, a3, d3, d4), d6, T, limits_arg(limits, 6));
}

// The answers of the batch closed forms, arrays as they were written; each unpacks as a tuple of
// them, in order.
struct ClosedBatch {
  py::array q, singular, within_limits;
  py::tuple values() const { return py::make_tuple(q, singular, within_limits); }
};
struct ClosedPath {
  py::array q, ok, reachable;
  py::tuple values() const { return py::make_tuple(q, ok, reachable); }
};

ClosedPath spherical_wrist_6r_path(ArrayLike targets_obj, double a2, double a3, double d3, double d4, double d1,
                                  double d6, ArrayLike q0_obj, LimitsLike limits) {
  const std::vector<Rigid> targets = rigid_frames(targets_obj, "targets");
  const long count = static_cast<long>(targets.size());
  const Vector q0 = as_vector(q0_obj, "q0", 6);
  const ArmGeometry g = arm_arg(d1, a2, a3, d3, d4);
  const JointLimits lim = limits_arg(limits, 6);
  py::array_t<double> q = new_array({static_cast<py::ssize_t>(count), 6});
  py::array_t<bool> ok = new_array<bool>({count}), reachable = new_array<bool>({count});
  double* qd = q.mutable_data();
  bool* okd = ok.mutable_data();
  bool* reachd = reachable.mutable_data();
  released("spherical wrist path", [&](Progress* progress) {
    ik_spherical_wrist_6r_path(g, d6, targets.data(), count, q0.data(), lim, qd, okd, reachd, progress);
  });
  return ClosedPath{q, ok, reachable};
}

// The UR family (robokin.closed.ur); limits: "default" (the chain's), None, or a pair.
ClosedFormSolutions ur(ArrayLike target, const Chain& chain, ChainLimitsLike limits) {
  const Rigid T = Rigid::from_matrix(as_transform(target, "target"));
  const std::optional<URArm>& arm = chain.closed_layout().ur;  // read once per chain
  JointLimits given;
  // Without the UR layout, ur_arm throws the ValueError naming what differs.
  return ik_ur(arm ? *arm : ur_arm(chain), chain, T, limits_or_default(chain, limits, 6, given));
}

py::array_t<double> solutions_q(const ClosedFormSolutions& s) { return array_of(s.row(0), {s.count(), s.dof}); }

// The rows within the limits, in order.
ClosedFormSolutions only_within_limits(const ClosedFormSolutions& s) {
  ClosedFormSolutions out;
  out.dof = s.dof;
  out.singular = s.singular;
  for (int k = 0; k < s.count(); ++k)
    if (s.within_limits[k]) out.add(s.row(k), s.postures[k]);
  return out;
}

// IKSolutions' pickled state: (version, dof, q (k, dof), postures, singular, within_limits).
auto solutions_state(const ClosedFormSolutions& s) {
  py::list postures, within;
  for (int k = 0; k < s.count(); ++k) postures.append(py::str(s.postures[k])), within.append(py::bool_(s.within_limits[k]));
  return py::make_tuple(kStateVersion, s.dof, solutions_q(s), py::tuple(postures), s.singular, py::tuple(within));
}

ClosedFormSolutions solutions_from_state(const py::tuple& t) {
  check_state(t, 6, "IKSolutions");
  // The labels are static strings in a solution: one interned copy of each label read back.
  static std::set<std::string> labels;
  static std::mutex labels_mutex;
  ClosedFormSolutions s;
  s.dof = t[1].cast<int>();
  s.singular = t[4].cast<bool>();
  const Array q = as_array(t[2], "q");
  const py::sequence postures = t[3].cast<py::sequence>(), within = t[5].cast<py::sequence>();
  if (s.dof < 1 || s.dof > ClosedFormSolutions::kMaxDof ||
      postures.size() > static_cast<size_t>(ClosedFormSolutions::kMaxSolutions) ||
      q.size() != static_cast<py::ssize_t>(postures.size()) * s.dof || within.size() != postures.size())
    fail("IKSolutions state: q must have one row of dof (1 to 7) values per posture and per within_limits "
         "flag, at most 8 rows");
  std::lock_guard<std::mutex> lock(labels_mutex);
  for (size_t k = 0; k < postures.size(); ++k)
    s.add(q.data() + k * s.dof, labels.insert(postures[k].cast<std::string>()).first->c_str(), within[k].cast<bool>());
  return s;
}

// ClosedBatch and ClosedPath: results that read as the tuples they were (unpacked, indexed, len 3).
template <class T>
void unpacks(py::class_<T>& cls) {
  cls.def("__iter__", [](const T& r) { return py::iter(r.values()); })
      .def("__getitem__", [](const T& r, py::object i) -> py::object { return r.values()[i]; })
      .def("__len__", [](const T& r) { return r.values().size(); });
}

void bind_batches(py::module_& m) {
  ResultClass<ClosedBatch>(m, "ClosedBatch",
                           "Answer of robokin.closed.ur_batch and ClosedSolver.solve_batch; unpacks as (q, singular,\n"
                           "within_limits).",
                           false)
      .value("q", &ClosedBatch::q,
             "(N, 8, dof) solution k of pose i in q[i, k], the slot of posture UR_POSTURES[k]; a NaN row where the\n"
             "slot holds none.")
      .value("singular", &ClosedBatch::singular, "(N,) booleans, True where pose i is at a singularity.")
      .value("within_limits", &ClosedBatch::within_limits,
             "(N, 8) booleans, True where the slot holds a solution within the limits.")
      .done_with(unpacks<ClosedBatch>);
  ResultClass<ClosedPath>(m, "ClosedPath", "Answer of robokin.closed.puma560_path; unpacks as (q, ok, reachable).",
                          false)
      .value("q", &ClosedPath::q, "(K, 6) the joints at each frame (the previous ones where ok is False).")
      .value("ok", &ClosedPath::ok, "(K,) booleans, True where the frame has a solution within the limits.")
      .value("reachable", &ClosedPath::reachable, "(K,) booleans, True where the frame has a solution, within the limits or not.")
      .done_with(unpacks<ClosedPath>);
}

// robokin.closed's IKSolutions.
void bind_solutions(py::module_& m) {
  py::class_<ClosedFormSolutions> cls(m, "IKSolutions",
                                      "Every closed-form solution of a pose: q (k, dof), one posture label per row and\n"
                                      "whether each row is within the joint limits (none is dropped for its limits).",
                                      py::dynamic_attr());
  def_kept(cls, "q", &solutions_q, "(k, dof) joint vectors, one per solution.");
  def_kept(
      cls, "within_limits",
      [](const ClosedFormSolutions& s) { return array_of(s.within_limits.data(), {s.count()}); },
      "(k,) booleans, True where row k is within the joint limits (shifted by 2 pi into them where that fits);\n"
      "False: some joint is outside its limits however it is shifted (revolute angles then in [-pi, pi]).");
  cls.def("only_within_limits", &only_within_limits,
          "The solutions within the joint limits only (an IKSolutions, rows in order).")
      .def_property_readonly(
          "postures",
          [](const ClosedFormSolutions& s) {
            py::list out;
            for (int k = 0; k < s.count(); ++k) out.append(py::str(s.postures[k]));
            return out;
          },
          "Posture label of each row of q.")
      .def_readonly("singular", &ClosedFormSolutions::singular,
                    "True at a singularity (postures coincide, or a joint is free: 0 was chosen).")
      .def_readonly("dof", &ClosedFormSolutions::dof)
      .def(py::pickle(  // (version, dof, q (k, dof), postures, singular, within_limits)
&solutions_state, &solutions_from_state))
      .def("__len__", &ClosedFormSolutions::count)
      .def(
          "nearest",
          [](const ClosedFormSolutions& s, ArrayLike q_obj) -> py::object {
            const Vector q = as_vector(q_obj, "q", s.dof);
            const int k = nearest_solution(s, q.data());
            if (k < 0) return py::none();
            return py::int_(k);
          },
          py::arg("q"),
          "Index of the solution within the limits nearest to q (Euclidean in joint space); None when none is.")
      .def("__repr__", [](py::handle self) { return printed("solutions_repr", self); });
}

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
  // q (N, 8, dof), singular (N,), within_limits (N, 8); dof is 7 with a held joint, else 6.
  ClosedBatch solve_batch(ArrayLike targets_obj) const {
    const std::vector<Rigid> targets = rigid_frames(targets_obj, "targets");
    const long count = static_cast<long>(targets.size());
    py::array_t<double> q = new_array({count, 8, chain().dof()});
    py::array_t<bool> within = new_array<bool>({count, 8}), singular = new_array<bool>({count});
    double* qd = q.mutable_data();
    bool* wd = within.mutable_data();
    bool* sd = singular.mutable_data();
    released("closed form", [&](Progress* progress) { solver.solve_batch(targets.data(), count, qd, wd, sd, progress); });
    return ClosedBatch{q, singular, within};
  }
};

// The solver of the chain (a Python Chain), or none when find finds no closed form.
std::unique_ptr<BoundSolver> bound_solver(py::object chain_obj, py::handle limits_obj, py::handle locked,
                                          const ClosedFamilyOptions& o, bool required) {
  const Chain& chain = chain_obj.cast<const Chain&>();
  JointLimits given;
  const JointLimits& limits = limits_or_default(chain, limits_obj, chain.dof(), given);
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
           "solve for targets, (N, 4, 4) frames, on every core, the GIL released -> ClosedBatch (q (N, 8, dof),\n"
           "singular (N,), within_limits (N, 8); it unpacks as that tuple), slots as robokin.closed.ur_batch's\n"
           "(UR_POSTURES); dof is 7 with a held joint (its value in its place), else 6.")
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

void bind_closed(py::module_& m) {
  bind_solutions(m);
  bind_batches(m);
  // No defaults here: robokin.closed's functions hold them and pass every argument.
  m.def("ik_planar_rp", &planar_rp, py::arg("target"), py::arg("limits"));
  m.def("ik_planar_2r", &planar_2r, py::arg("target"), py::arg("a1"), py::arg("a2"), py::arg("limits"));
  m.def("ik_planar_3r", &planar_3r, py::arg("target"), py::arg("a1"), py::arg("a2"), py::arg("a3"), py::arg("method"),
        py::arg("limits"));
  m.def("ik_anthropomorphic", &anthropomorphic, py::arg("target"), py::arg("a2"), py::arg("a3"), py::arg("d1"),
        py::arg("limits"));
  m.def("ik_spherical_wrist_6r_path", &spherical_wrist_6r_path, py::arg("targets"), py::arg("a2"), py::arg("a3"),
        py::arg("d3"), py::arg("d4"), py::arg("d1"), py::arg("d6"), py::arg("q0"), py::arg("limits"));
  m.def("ik_spherical_wrist_6r", &spherical_wrist_6r, py::arg("target"), py::arg("a2"), py::arg("a3"), py::arg("d3"),
        py::arg("d4"), py::arg("d1"), py::arg("d6"), py::arg("limits"));
  m.def("ik_ur", &ur, py::arg("target"), py::arg("chain"), py::arg("limits"));
  {
    py::list names;
    for (const char* p : kURPostures) names.append(py::str(p));
    m.attr("UR_POSTURES") = py::tuple(names);
  }
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
