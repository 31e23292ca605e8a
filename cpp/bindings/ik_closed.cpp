// Closed-form inverse kinematics: every solution, labelled by posture (use robokin.closed).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "closed_parts.hpp"
#include "progress.hpp"
#include "results.hpp"

#include "robokin/ik_closed.hpp"

#include <pybind11/stl.h>

#include <mutex>
#include <set>

#include <vector>

namespace robokin::bind {
namespace {

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

ClosedFormSolutions spherical_wrist(ArrayLike target, double a2, double a3, double d3, double d4, double d1,
                                    double d6, LimitsLike limits) {
  const Rigid T = Rigid::from_matrix(as_transform(target, "target"));
  return ik_spherical_wrist(arm_arg(d1, a2, a3, d3, d4), d6, T, limits_arg(limits, 6));
}

py::tuple spherical_wrist_path(ArrayLike targets_obj, double a2, double a3, double d3, double d4, double d1,
                               double d6, ArrayLike q0_obj, LimitsLike limits) {
  const Array a = rows_arg(targets_obj, "targets", {4, 4});
  const long count = a.shape(0);
  std::vector<Rigid> targets;
  for (long k = 0; k < count; ++k) targets.push_back(Rigid::from_matrix(rigid_at(a.data() + 16 * k, "targets")));
  const Vector q0 = as_vector(q0_obj, "q0", 6);
  const ArmGeometry g = arm_arg(d1, a2, a3, d3, d4);
  const JointLimits lim = limits_arg(limits, 6);
  py::array_t<double> q = new_array({static_cast<py::ssize_t>(count), 6});
  py::array_t<bool> ok = new_array<bool>({count}), reachable = new_array<bool>({count});
  double* qd = q.mutable_data();
  bool* okd = ok.mutable_data();
  bool* reachd = reachable.mutable_data();
  released("spherical wrist path", [&](Progress* progress) {
    ik_spherical_wrist_path(g, d6, targets.data(), count, q0.data(), lim, qd, okd, reachd, progress);
  });
  return py::make_tuple(q, ok, reachable);
}

// The UR family (robokin.closed.ur); limits: "default" (the chain's), None, or a pair.
ClosedFormSolutions ur(ArrayLike target, const Chain& chain, ChainLimitsLike limits) {
  const Rigid T = Rigid::from_matrix(as_transform(target, "target"));
  const std::optional<URArm>& arm = chain.closed_layout().ur;  // read once per chain
  // Without the UR layout, ur_arm throws the ValueError naming what differs.
  return ik_ur(arm ? *arm : ur_arm(chain), chain, T, limits_or_default(chain, limits, 6));
}

}  // namespace

std::vector<Rigid> rigid_frames(ArrayLike targets_obj, const char* name) {
  const Array a = rows_arg(targets_obj, name, {4, 4}, "N");
  const long count = a.shape(0);
  std::vector<Rigid> targets(count);
  for (long k = 0; k < count; ++k) {
    const double* m = a.data() + 16 * k;
    if (!is_rigid(m)) fail(std::string(name) + ": frame " + std::to_string(k) + " is not a rigid transform");
    targets[k] = Rigid::from_matrix(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m));
  }
  return targets;
}

namespace {

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
      "(k,) booleans: row k is within the joint limits (shifted by 2 pi into them where that fits);\n"
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

}  // namespace

void bind_ik_closed(py::module_& m) {
  bind_solutions(m);
  m.def("ik_planar_rp", &planar_rp, py::arg("target"), py::arg("limits") = py::none());
  m.def("ik_planar_2r", &planar_2r, py::arg("target"), py::arg("a1"), py::arg("a2"), py::arg("limits") = py::none());
  m.def("ik_planar_3r", &planar_3r, py::arg("target"), py::arg("a1"), py::arg("a2"), py::arg("a3"),
        py::arg("method") = "algebraic", py::arg("limits") = py::none());
  m.def("ik_anthropomorphic", &anthropomorphic, py::arg("target"), py::arg("a2"), py::arg("a3"), py::arg("d1") = 0.0,
        py::arg("limits") = py::none());
  m.def("ik_spherical_wrist_path", &spherical_wrist_path, py::arg("targets"), py::arg("a2"), py::arg("a3"),
        py::arg("d3"), py::arg("d4"), py::arg("d1"), py::arg("d6"), py::arg("q0"), py::arg("limits") = py::none());
  m.def("ik_spherical_wrist", &spherical_wrist, py::arg("target"), py::arg("a2"), py::arg("a3"), py::arg("d3"),
        py::arg("d4"), py::arg("d1") = 0.0, py::arg("d6") = 0.0, py::arg("limits") = py::none());
  m.def("ik_ur", &ur, py::arg("target"), py::arg("chain"), py::arg("limits") = "default");
  {
    py::list names;
    for (const char* p : kURPostures) names.append(py::str(p));
    m.attr("UR_POSTURES") = py::tuple(names);
  }
}

}  // namespace robokin::bind
