// robokin.RRR3: the planar 3-RRR parallel robot of the 3-RRR project, its inverse and forward
// models, Jacobians and singularities; its planners are the class's second part (rrr3_parts.hpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"
#include "rrr3_parts.hpp"

#include "robokin/rrr3.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace robokin::bind {
namespace {

using Elbows = Eigen::Matrix<double, 3, 2>;

py::array_t<double> ik_batch(const RRR3& r, ArrayLike poses_obj, ModeLike mode_obj) {
  const Mode mode = as_mode(mode_obj);
  const Array poses = rows_arg(poses_obj, "poses", {3}, "N");
  const long n = static_cast<long>(poses.shape(0));
  py::array_t<double> out = new_array({n, 3});
  double* dst = out.mutable_data();
  const double* src = poses.data();
  released("RRR3.ik_batch", [&](Progress* progress) { r.ik_batch(src, n, mode, dst, progress); });
  return out;
}

py::array_t<double> ik_all(const RRR3& r, ArrayLike pose_obj) {
  const Pose pose = as_pose(pose_obj);
  py::array_t<double> out = new_array({8, 3});
  for (int k = 0; k < 8; ++k) {
    double* row = out.mutable_data() + 3 * k;
    if (r.ik(pose, RRR3::mode_at(k), row) >= 0) row[0] = row[1] = row[2] = NAN;
  }
  return out;
}

RRR3Newton ik_newton(const RRR3& r, ArrayLike pose_obj, ArrayLike guess_obj, const py::kwargs& kwargs) {
  const Pose pose = as_pose(pose_obj);
  Array g = as_array(guess_obj, "guess");
  if (g.size() != 6 || !(g.ndim() == 1 || (g.ndim() == 2 && g.shape(0) == 2)))
    fail("guess: expected (alpha, beta) as shape (2, 3) or (6,), got " + shape_of(g));
  require_finite(g.data(), 6, "guess");
  return r.ik_newton(pose, Eigen::Map<const Eigen::Vector3d>(g.data()), Eigen::Map<const Eigen::Vector3d>(g.data() + 3),
                     options_arg<RRR3NewtonOptions>(kwargs));
}

RRR3Fk fk(const RRR3& r, ArrayLike alpha_obj, ArrayLike guess_obj, const py::kwargs& kwargs) {
  const Eigen::Vector3d alpha = as_vector(alpha_obj, "alpha", 3);
  const Pose guess = as_pose(guess_obj, "guess");
  return r.fk(alpha, guess, options_arg<RRR3NewtonOptions>(kwargs));
}

py::array_t<double> fk_all(const RRR3& r, ArrayLike alpha_obj) {
  const Eigen::Vector3d alpha = as_vector(alpha_obj, "alpha", 3);
  const std::vector<Pose> poses = released([&] { return r.fk_all(alpha); });
  py::array_t<double> out = new_array({static_cast<py::ssize_t>(poses.size()), 3});
  for (size_t k = 0; k < poses.size(); ++k) std::copy(poses[k].data(), poses[k].data() + 3, out.mutable_data() + 3 * k);
  return out;
}

py::dict points(const RRR3& r, ArrayLike pose_obj, ModeLike mode_obj) {
  const Pose pose = as_pose(pose_obj);
  const Elbows A = r.elbows(r.ik_or_throw(pose, as_mode(mode_obj)));
  Elbows O, B;
  for (int i = 0; i < 3; ++i) {
    O.row(i) = r.base_joint(i).transpose();
    B.row(i) = r.platform_joint(pose, i).transpose();
  }
  py::dict d;
  d["O"] = to_numpy(O);
  d["A"] = to_numpy(A);
  d["B"] = to_numpy(B);
  return d;
}

py::tuple jacobians(const RRR3& r, ArrayLike pose_obj, ModeLike mode_obj) {
  Eigen::Matrix3d A, B;
  r.jacobians(as_pose(pose_obj), as_mode(mode_obj), A, B);
  return py::make_tuple(to_numpy(A), to_numpy(B));
}


// The answers of ik_newton, fk and singularity.
void bind_kinematics_results(py::module_& m) {
  ResultClass<RRR3Newton>(m, "RRR3Newton", "Answer of RRR3.ik_newton; unpacks as (alpha, beta).", false)
      .fields()
      .done_with([](py::class_<RRR3Newton>& cls) {
        cls.def("__iter__", [](py::handle self) { return py::iter(py::make_tuple(self.attr("alpha"), self.attr("beta"))); });
      });
  ResultClass<RRR3Fk>(m, "RRR3Fk", "Answer of RRR3.fk.", false).fields().done();
  ResultClass<RRR3Singularity>(m, "RRR3Singularity", "Answer of RRR3.singularity.", false)
      .fields()
      .value_as("leg", [](const RRR3Singularity& s) { return s.leg < 0 ? std::nullopt : std::optional<int>(s.leg); },
                [](RRR3Singularity& s, py::handle v) { s.leg = v.is_none() ? -1 : v.cast<int>(); },
                "The stretched or folded leg of a serial singularity, else None.")
      .value_as("lines", [](const RRR3Singularity& s) { return s.lines.empty() ? std::nullopt : std::optional<std::string>(s.lines); },
                [](RRR3Singularity& s, py::handle v) { s.lines = v.is_none() ? "" : v.cast<std::string>(); },
                "For a parallel singularity: 'parallel' or 'concurrent' lines A_iB_i, else None.")
      .done();
}


// RRR3_DEFAULTS: the seed's robot and the shared thresholds, read-only.
void bind_defaults(py::module_& m) {
  py::dict defaults;
  defaults["base_radius"] = kDefaultBaseRadius;
  defaults["platform_radius"] = kDefaultPlatformRadius;
  defaults["l1"] = kDefaultL1;
  defaults["l2"] = kDefaultL2;
  defaults["singular_tol"] = kSingularTol;
  defaults["near_distance"] = kNearDistance;
  defaults["serial_margin"] = kSerialMargin;
  m.attr("RRR3_DEFAULTS") = py::module_::import("types").attr("MappingProxyType")(defaults);
}


// RRR3's constructor, lengths, base joints and modes.
void def_geometry(py::class_<RRR3>& cls) {
  cls.def(py::init([](double rb, double re, double l1, double l2) { return RRR3(rb, re, l1, l2); }),
           py::arg("base_radius") = kDefaultBaseRadius, py::arg("platform_radius") = kDefaultPlatformRadius,
           py::arg("l1") = kDefaultL1, py::arg("l2") = kDefaultL2)
      .def_property_readonly("base_radius", &RRR3::base_radius)
      .def_property_readonly("platform_radius", &RRR3::platform_radius)
      .def_property_readonly("l1", &RRR3::l1)
      .def_property_readonly("l2", &RRR3::l2)
      .def_property_readonly(
          "base_joints",
          [](const RRR3& r) {
            Elbows o;
            for (int i = 0; i < 3; ++i) o.row(i) = r.base_joint(i).transpose();
            py::array_t<double> out = to_numpy(o);
            set_read_only(out);
            return out;
          },
          "(3, 2) base joints O_i = R_b (cos t_i, sin t_i), t_i = -90 deg + 120 deg i (read-only).")
      .def_property_readonly_static("modes", [](py::object) {
        py::list modes;
        for (int k = 0; k < 8; ++k) {
          const Mode md = RRR3::mode_at(k);
          modes.append(py::make_tuple(md[0], md[1], md[2]));
        }
        return py::tuple(modes);
      }, "The 8 working modes (m_0, m_1, m_2), m_i = sign(beta_i), in ik_all's row order.");
}

// RRR3's inverse and forward models, drawing points, Jacobians and singularities.
void def_kinematics(py::class_<RRR3>& cls) {
  static const std::string ik_newton_doc = kwargs_doc<RRR3NewtonOptions>(
      "ik_newton(pose, guess, *", "Newton-Raphson on the 6 loop equations from guess (alpha, beta).");
  static const std::string fk_doc =
      kwargs_doc<RRR3NewtonOptions>("fk(alpha, guess, *", "One assembly mode by Newton from a guess pose.");
  cls.def("ik", [](const RRR3& r, ArrayLike pose, ModeLike mode) {
        return to_numpy(Eigen::VectorXd(r.ik_or_throw(as_pose(pose), as_mode(mode))));
      }, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "Actuated angles (3,) for pose (x, y, phi) in working mode mode (m_0, m_1, m_2) of +-1;\n"
           "UnreachableError names the leg that cannot reach.")
      .def("ik_all", &ik_all, py::arg("pose"), "(8, 3) actuated angles for pose (x, y, phi): row k for mode k of RRR3.modes, NaN where\n"
           "unreachable.")
      .def("ik_batch", &ik_batch, py::arg("poses"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "(N, 3) actuated angles for (N, 3) poses in working mode mode, NaN rows where a leg cannot\n"
           "reach (GIL released).")
      .def("ik_newton", &ik_newton, py::arg("pose"), py::arg("guess"), ik_newton_doc.c_str())
      .def("fk", &fk, py::arg("alpha"), py::arg("guess"), fk_doc.c_str())
      .def("fk_all", &fk_all, py::arg("alpha"),
           "(k, 3) every assembly mode, k <= 6, sorted by phi; each once (a double root at a parallel\n"
           "singularity too; modes closer than the loops can tell in floating point, some 1e-7 of the\n"
           "size, as one). Where the elbows form a triangle congruent to the platform's (e.g. equal\n"
           "alpha_i when base_radius == platform_radius) the platform also moves on a continuum (phi\n"
           "fixed, E on a circle of radius l2): those poses are not returned, only the isolated modes.")
      .def("points", &points, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "Joint positions at pose in working mode mode, for drawing: dict of (3, 2) arrays 'O', 'A', 'B'.")
      .def("jacobians", &jacobians, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "The seed's (A, B) at pose in working mode mode: A v = B alpha_dot with v = (v_x, v_y, w) in\n"
           "the effector frame.")
      .def("singularity", [](const RRR3& r, ArrayLike pose, ModeLike mode, double tol) {
        return r.singularity(as_pose(pose), as_mode(mode), tol);
      }, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode), py::arg("tol") = kSingularTol,
           "The singularity at pose in working mode mode: its kind ('none', 'parallel', 'serial') with\n"
           "tol on the normalised determinants.");
}


// RRR3 as a value: pickle, equality, hash, repr.
void def_value(py::class_<RRR3>& cls) {
  cls.def(py::pickle(  // (version, base_radius, platform_radius, l1, l2)
          [](const RRR3& r) { return py::make_tuple(kStateVersion, r.base_radius(), r.platform_radius(), r.l1(), r.l2()); },
          [](const py::tuple& t) {
            check_state(t, 5, "RRR3");
            return RRR3(t[1].cast<double>(), t[2].cast<double>(), t[3].cast<double>(), t[4].cast<double>());
          }))
      .def(
          "__eq__",
          [](const RRR3& a, const RRR3& b) {
            return a.base_radius() == b.base_radius() && a.platform_radius() == b.platform_radius() &&
                   a.l1() == b.l1() && a.l2() == b.l2();
          },
          py::is_operator())
      .def("__hash__", [](const RRR3& r) {
        return py::hash(py::make_tuple(r.base_radius(), r.platform_radius(), r.l1(), r.l2()));
      })
      .def("__repr__", [](py::handle self) { return printed("rrr3_repr", self); });
}


}  // namespace

void bind_rrr3(py::module_& m) {
  OptionsClass<RRR3NewtonOptions>(m, "RRR3NewtonOptions", "The options of RRR3.ik_newton and RRR3.fk (keywords).")
      .fields();
  bind_kinematics_results(m);
  bind_defaults(m);
  py::class_<RRR3> cls(m, "RRR3",
                       "The planar 3-RRR parallel robot (the 3-RRR project): base joints on a circle of\n"
                       "base_radius, platform joints on one of platform_radius, legs of links l1 (actuated)\n"
                       "and l2 (m); the seed's robot by default.");
  def_geometry(cls);
  def_kinematics(cls);
  def_rrr3_planning(m, cls);
  def_value(cls);
}

}  // namespace robokin::bind
