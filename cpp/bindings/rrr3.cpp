// robokin.RRR3: the planar 3-RRR parallel robot of the 3-RRR project.
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"

#include "robokin/rrr3.hpp"
#include "robokin/rrr3_connect.hpp"
#include "robokin/rrr3_loop.hpp"
#include "robokin/rrr3_plan.hpp"
#include "robokin/rrr3_workspace.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace robokin::bind {
namespace {

using Elbows = Eigen::Matrix<double, 3, 2>;

Mode as_mode(py::handle obj) {
  Array a = as_array(obj, "mode");
  if (a.ndim() != 1 || a.shape(0) != 3) fail("mode: expected 3 signs (m_0, m_1, m_2), got shape " + shape_of(a));
  Mode m;
  for (int i = 0; i < 3; ++i) {
    const double v = a.data()[i];
    if (v != 1.0 && v != -1.0) fail("mode: every entry must be +1 or -1, got " + std::to_string(v));
    m[i] = static_cast<int>(v);
  }
  return m;
}

}  // namespace

// The working mode as an options field: a tuple of signs in Python.
template <>
struct FieldCodec<Mode> {
  static constexpr bool defined = true;
  using Arg = ModeLike;
  static std::string kind() { return "(m_0, m_1, m_2) of +-1"; }
  static py::tuple to_python(const Mode& m) { return py::make_tuple(m[0], m[1], m[2]); }
  static Mode from_python(py::handle obj, const char*) { return as_mode(obj); }
};

namespace {

// A finite pose (x, y, phi) with |x|, |y| <= 1e100 m: squared distances to it stay finite, so the
// closure errors of ik_newton and fk do (ik_batch gives NaN rows for any farther pose).
Pose as_pose(py::handle obj, const char* name = "pose") {
  const Pose p = as_vector(obj, name, 3);
  if (!(std::abs(p(0)) <= 1e100 && std::abs(p(1)) <= 1e100)) fail(std::string(name) + ": x and y must be within 1e100 m");
  return p;
}

// Python's repr of a float: the shortest text that reads back as the same number.
std::string exact_number(double v) { return py::repr(py::float_(v)).cast<std::string>(); }


py::array_t<double> rows32(const Elbows& m) { return to_numpy(Eigen::MatrixXd(m)); }

py::array_t<double> ik_batch(const RRR3& r, ArrayLike poses_obj, ModeLike mode_obj) {
  const Mode mode = as_mode(mode_obj);
  Array poses = as_array(poses_obj, "poses");
  if (poses.ndim() != 2 || poses.shape(1) != 3) fail("poses: expected shape (N, 3), got " + shape_of(poses));
  require_finite(poses.data(), poses.size(), "poses");
  const long n = static_cast<long>(poses.shape(0));
  py::array_t<double> out = new_array({n, 3});
  double* dst = out.mutable_data();
  const double* src = poses.data();
  PythonProgress progress("RRR3.ik_batch");
  {
    py::gil_scoped_release release;
    r.ik_batch(src, n, mode, dst, &progress);
  }
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

RRR3Newton ik_newton(const RRR3& r, ArrayLike pose_obj, ArrayLike guess_obj, int max_iter, double tol) {
  const Pose pose = as_pose(pose_obj);
  Array g = as_array(guess_obj, "guess");
  if (g.size() != 6 || !(g.ndim() == 1 || (g.ndim() == 2 && g.shape(0) == 2)))
    fail("guess: expected (alpha, beta) as shape (2, 3) or (6,), got " + shape_of(g));
  require_finite(g.data(), 6, "guess");
  return r.ik_newton(pose, Eigen::Map<const Eigen::Vector3d>(g.data()), Eigen::Map<const Eigen::Vector3d>(g.data() + 3),
                     max_iter, tol);
}

RRR3Fk fk(const RRR3& r, ArrayLike alpha_obj, ArrayLike guess_obj, int max_iter, double tol) {
  const Eigen::Vector3d alpha = as_vector(alpha_obj, "alpha", 3);
  const Pose guess = as_pose(guess_obj, "guess");
  return r.fk(alpha, guess, max_iter, tol);
}

py::array_t<double> fk_all(const RRR3& r, ArrayLike alpha_obj) {
  const Eigen::Vector3d alpha = as_vector(alpha_obj, "alpha", 3);
  std::vector<Pose> poses;
  {
    py::gil_scoped_release release;
    poses = r.fk_all(alpha);
  }
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
  d["O"] = rows32(O);
  d["A"] = rows32(A);
  d["B"] = rows32(B);
  return d;
}

py::tuple jacobians(const RRR3& r, ArrayLike pose_obj, ModeLike mode_obj) {
  Eigen::Matrix3d A, B;
  r.jacobians(as_pose(pose_obj), as_mode(mode_obj), A, B);
  return py::make_tuple(to_numpy(Eigen::MatrixXd(A)), to_numpy(Eigen::MatrixXd(B)));
}

using PlanOptionsClass = OptionsClass<RRR3PlanOptions>;
using ConnectOptionsClass = OptionsClass<RRR3ConnectOptions>;
using LoopOptionsClass = OptionsClass<RRR3LoopOptions>;

RRR3Plan plan(const RRR3& r, ArrayLike points_obj, const py::kwargs& kwargs) {
  Array pts = as_array(points_obj, "points");
  if (pts.ndim() != 2 || pts.shape(1) != 2) fail("points: expected shape (K, 2), got " + shape_of(pts));
  require_finite(pts.data(), pts.size(), "points");
  const RRR3PlanOptions o = PlanOptionsClass::from_kwargs(kwargs);
  o.validate();
  const long count = static_cast<long>(pts.shape(0));
  // The sizes (grid memory, work of the dynamic programme) are bounded by plan_path itself.
  PythonProgress progress("RRR3.plan");
  py::gil_scoped_release release;
  return plan_path(r, pts.data(), count, o, &progress);
}

// plan_loop(points, **kwargs): the loop's own options (sign, nominals) and the plan's (all but phi,
// searched, and closed, always true).
RRR3Loop loop_plan(const RRR3& r, ArrayLike points_obj, const py::kwargs& kwargs) {
  Array pts = as_array(points_obj, "points");
  if (pts.ndim() != 2 || pts.shape(1) != 2) fail("points: expected shape (K, 2), got " + shape_of(pts));
  require_finite(pts.data(), pts.size(), "points");
  const std::vector<std::string> loop_names = field_names<RRR3LoopOptions>();
  std::vector<std::string> plan_names;
  for (const std::string& n : field_names<RRR3PlanOptions>())
    if (n != "phi" && n != "closed") plan_names.push_back(n);  // phi is searched, the plan always closed
  auto has = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  py::dict loop_kwargs, plan_kwargs;
  for (auto item : kwargs) {
    const std::string name = py::str(item.first).cast<std::string>();
    if (!has(loop_names, name) && !has(plan_names, name)) {
      std::string all;
      for (const std::string& n : loop_names) all += (all.empty() ? "" : ", ") + n;
      for (const std::string& n : plan_names) all += ", " + n;
      throw py::type_error("unexpected keyword argument '" + name + "' (options: " + all +
                           "; phi is searched over nominals, the plan is always closed)");
    }
    (has(loop_names, name) ? loop_kwargs : plan_kwargs)[item.first] = item.second;
  }
  const RRR3LoopOptions loop = LoopOptionsClass::from_kwargs(loop_kwargs);
  const RRR3PlanOptions o = PlanOptionsClass::from_kwargs(plan_kwargs);
  loop.validate();
  o.validate();
  const long count = static_cast<long>(pts.shape(0));
  PythonProgress progress("RRR3.plan_loop");
  py::gil_scoped_release release;
  return plan_loop(r, pts.data(), count, o, loop, &progress);
}

RRR3Plan connect_poses(const RRR3& r, ArrayLike start_obj, ArrayLike goal_obj, const py::kwargs& kwargs) {
  const Pose start = as_pose(start_obj, "start"), goal = as_pose(goal_obj, "goal");
  const RRR3ConnectOptions o = ConnectOptionsClass::from_kwargs(kwargs);
  o.validate();
  PythonProgress progress("RRR3.connect");
  py::gil_scoped_release release;
  return connect(r, start, goal, o, &progress);
}

using WorkspaceOptionsClass = OptionsClass<RRR3WorkspaceOptions>;

// The options of one map, from the call's keyword arguments.
RRR3WorkspaceOptions workspace_options(const py::kwargs& kwargs) {
  const RRR3WorkspaceOptions o = WorkspaceOptionsClass::from_kwargs(kwargs);
  o.validate();
  return o;
}

RRR3Workspace workspace_map(const RRR3& r, const py::kwargs& kwargs) {
  const RRR3WorkspaceOptions o = workspace_options(kwargs);
  PythonProgress progress("RRR3.workspace");
  py::gil_scoped_release release;
  return workspace(r, o, &progress);
}

py::array_t<double> study_areas(ArrayLike robots_obj, const py::kwargs& kwargs) {
  Array g = as_array(robots_obj, "robots");
  if (g.ndim() != 2 || g.shape(1) != 4)
    fail("robots: expected shape (K, 4) rows (base_radius, platform_radius, l1, l2), got " + shape_of(g));
  std::vector<RRR3> robots;
  for (py::ssize_t k = 0; k < g.shape(0); ++k) {
    const double* row = g.data() + 4 * k;
    try {
      robots.emplace_back(row[0], row[1], row[2], row[3]);
    } catch (const std::invalid_argument& e) {
      fail("robots[" + std::to_string(k) + "]: " + e.what());
    }
  }
  const RRR3WorkspaceOptions o = workspace_options(kwargs);
  std::vector<double> areas;
  PythonProgress progress("design study");
  {
    py::gil_scoped_release release;
    areas = region_areas(robots, o, &progress);
  }
  return to_numpy(Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(areas.data(), areas.size())));
}

// The core's exceptions that carry data, as robokin.errors classes with that data as attributes.
void register_errors() {
  // LegUnreachable -> robokin.UnreachableError (a ValueError) with the leg as an attribute. The
  // class is looked up when raised, so the import order of the package does not matter.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const LegUnreachable& e) {
      py::object cls = py::module_::import("robokin.errors").attr("UnreachableError");
      py::object exc = cls(e.what());
      exc.attr("leg") = e.leg();
      PyErr_SetObject(cls.ptr(), exc.ptr());
    } catch (const NoRoute& e) {
      py::object cls = py::module_::import("robokin.errors").attr("NoRouteError");
      py::object exc = cls(e.what());
      exc.attr("reason") = e.reason();
      PyErr_SetObject(cls.ptr(), exc.ptr());
    }
  });
}

// The answers of ik_newton, fk and singularity.
void bind_kinematics_results(py::module_& m) {
  ResultClass<RRR3Newton>(m, "RRR3Newton", "Answer of RRR3.ik_newton; unpacks as (alpha, beta).", false)
      .array("alpha", &RRR3Newton::alpha, "Actuated angles (3,) (rad).")
      .array("beta", &RRR3Newton::beta, "Elbow angles (3,) (rad), link 1 to link 2.")
      .value("converged", &RRR3Newton::converged, "The residual fell below tol.")
      .value("iterations", &RRR3Newton::iterations, "Newton steps taken.")
      .value("error", &RRR3Newton::error, "Largest loop-closure residual (m).")
      .done_with([](py::class_<RRR3Newton>& cls) {
        cls.def("__iter__", [](py::handle self) { return py::iter(py::make_tuple(self.attr("alpha"), self.attr("beta"))); });
      });
  ResultClass<RRR3Fk>(m, "RRR3Fk", "Answer of RRR3.fk.", false)
      .array("pose", &RRR3Fk::pose, "The pose (x, y, phi) found.")
      .value("converged", &RRR3Fk::converged, "The residual fell below tol.")
      .value("iterations", &RRR3Fk::iterations, "Newton steps taken.")
      .value("error", &RRR3Fk::error, "Largest | |A_i B_i| - l2 | (m).")
      .done();
  ResultClass<RRR3Singularity>(m, "RRR3Singularity", "Answer of RRR3.singularity.", false)
      .value("kind", &RRR3Singularity::kind, "'none', 'parallel' or 'serial'.")
      .value("det_a", &RRR3Singularity::det_a, "det A.")
      .value("det_b", &RRR3Singularity::det_b, "det B.")
      .value("det_a_norm", &RRR3Singularity::det_a_norm, "det A / platform_radius.")
      .value("det_b_norm", &RRR3Singularity::det_b_norm, "det B / l1^3.")
      .value("distance", &RRR3Singularity::distance,
             "Inverse condition number of A (third column / platform_radius): 0 at a parallel singularity.")
      .value_as("leg", [](const RRR3Singularity& s) { return s.leg < 0 ? std::nullopt : std::optional<int>(s.leg); },
                [](RRR3Singularity& s, py::handle v) { s.leg = v.is_none() ? -1 : v.cast<int>(); },
                "The stretched or folded leg of a serial singularity, else None.")
      .value_as("lines", [](const RRR3Singularity& s) { return s.lines.empty() ? std::nullopt : std::optional<std::string>(s.lines); },
                [](RRR3Singularity& s, py::handle v) { s.lines = v.is_none() ? "" : v.cast<std::string>(); },
                "For a parallel singularity: 'parallel' or 'concurrent' lines A_iB_i, else None.")
      .done();
}

// The answers of plan, connect and plan_loop.
void bind_plan_results(py::module_& m) {
  ResultClass<RRR3Plan>(m, "RRR3Plan", "Answer of RRR3.plan and RRR3.connect: the poses to follow and what they give.", false)
      .array("poses", &RRR3Plan::poses, "(K, 3) poses (x, y, phi).")
      .array("alpha", &RRR3Plan::alpha, "(K, 3) actuated angles, NaN rows where unreachable (feasible is then False).")
      .array("det_a_norm", &RRR3Plan::det_a_norm, "det A / platform_radius along the path, NaN where unreachable.")
      .array("det_b_norm", &RRR3Plan::det_b_norm, "det B / l1^3 along the path, NaN where unreachable.")
      .array("distance", &RRR3Plan::distance,
             "Distance to parallel singularities (inverse condition number of A) along the path, NaN where\n"
             "unreachable.")
      .value("sign", &RRR3Plan::sign, "The sign of det A kept along the path.")
      .value("feasible", &RRR3Plan::feasible,
             "Every pose reachable, clear of serial singularities, at distance >= margin, one sign of det A.")
      .done();
  ResultClass<RRR3Loop>(m, "RRR3Loop", "Answer of RRR3.plan_loop: the closed plan and the nominal orientation it is about.", false)
      .value("plan", &RRR3Loop::plan, "The closed RRR3Plan about nominal (no poses when none was found).")
      .value_as("nominal", [](const RRR3Loop& l) { return l.found ? std::optional<double>(l.nominal) : std::nullopt; },
                [](RRR3Loop& l, py::handle v) { l.nominal = v.is_none() ? std::nan("") : v.cast<double>(); },
                "The nominal orientation used (rad), None when none was found.")
      .value("found", &RRR3Loop::found, "A nominal orientation suited.")
      .value_as("reason", [](const RRR3Loop& l) { return l.found ? std::nullopt : std::optional<std::string>(l.reason); },
                [](RRR3Loop& l, py::handle v) { l.reason = v.is_none() ? "" : v.cast<std::string>(); },
                "Why none was found: 'start' (no nominal puts the first point on the side) or 'plan'; None when found.")
      .done();
}

// The cells of a workspace map as (n, n) codes; unpickled from the array, or from the bytes of
// an earlier state.
py::array_t<std::uint8_t> workspace_cells(const RRR3Workspace& w) {
  py::array_t<std::uint8_t> out({w.n, w.n});
  std::copy(w.cells.begin(), w.cells.end(), out.mutable_data());
  return out;
}

void restore_cells(RRR3Workspace& w, py::handle v) {
  std::vector<std::uint8_t> cells;
  if (py::isinstance<py::bytes>(v)) {
    const std::string s = v.cast<std::string>();
    cells.assign(s.begin(), s.end());
  } else if (const auto a = aligned_array<std::uint8_t>(v)) {
    cells.assign(a.data(), a.data() + a.size());
  }
  if (w.n < 0 || cells.size() != static_cast<size_t>(w.n * w.n)) fail("state: cells: n * n cell codes expected");
  w.cells = std::move(cells);
}

// RRR3Workspace: workspace's answer.
void bind_workspace_result(py::module_& m) {
  ResultClass<RRR3Workspace>(m, "RRR3Workspace", "Answer of RRR3.workspace: a constant-orientation map.", false)
      .value("n", &RRR3Workspace::n, "n x n cells.")
      .value("x0", &RRR3Workspace::x0, "x of the grid's lower-left corner (m).")
      .value("y0", &RRR3Workspace::y0, "y of the grid's lower-left corner (m).")
      .value("cell_size", &RRR3Workspace::h, "The cells' side (m).")
      .value_as("cells", &workspace_cells, &restore_cells,
                "(n, n) codes, row j at y[j], column i at x[i]: 0 unreachable, 1 regular, 2 parallel, 3 serial.")
      .value("reachable_area", &RRR3Workspace::reachable_area, "Area of the reachable cells (m^2).")
      .value("regular_area", &RRR3Workspace::regular_area, "Area of the reachable, non-singular cells (m^2).")
      .value("area", &RRR3Workspace::region_area, "Area of the largest singularity-free 4-connected region (m^2).")
      .done_with([](py::class_<RRR3Workspace>& cls) {
        cls.def_property_readonly("x", [](const RRR3Workspace& w) { return to_numpy(w.x()); }, "Cell centres along x (n,).")
            .def_property_readonly("y", [](const RRR3Workspace& w) { return to_numpy(w.y()); }, "Cell centres along y (n,).")
            .def_property_readonly("extent", [](const RRR3Workspace& w) { return py::tuple(py::cast(w.extent())); },
                                   "(x_min, x_max, y_min, y_max) of the grid, for matplotlib's imshow.");
      });
}

// The options structs of plan, workspace, connect and plan_loop, from their headers' field lists.
void bind_options(py::module_& m) {
  PlanOptionsClass(m, "RRR3PlanOptions", "The options of RRR3.plan (keywords); defaults as in the seed's simulator.").fields();
  WorkspaceOptionsClass(m, "RRR3WorkspaceOptions", "The options of RRR3.workspace (its arguments, one map's).").fields();
  ConnectOptionsClass(m, "RRR3ConnectOptions", "The options of RRR3.connect (keywords).").fields();
  LoopOptionsClass(m, "RRR3LoopOptions", "The options of RRR3.plan_loop of its own (keywords); the plan's are RRR3PlanOptions'.")
      .fields();
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

// rrr3_region_areas: the design study's areas (robokin.rrr3_design).
void bind_design_study(py::module_& m) {
  static const std::string doc = keyword_list<RRR3WorkspaceOptions>("rrr3_region_areas(robots, *") + "\n\n"
      "RRR3Workspace.area for each row (base_radius, platform_radius, l1, l2) of robots, on the maps of the\n"
      "options (RRR3WorkspaceOptions). Use robokin.rrr3_design.";
  m.def("rrr3_region_areas", &study_areas, py::arg("robots"), doc.c_str());
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
            py::array_t<double> out = rows32(o);
            out.attr("setflags")(py::arg("write") = false);
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
  cls.def("ik", [](const RRR3& r, ArrayLike pose, ModeLike mode) {
        return to_numpy(Eigen::VectorXd(r.ik_or_throw(as_pose(pose), as_mode(mode))));
      }, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "Actuated angles (3,) for pose (x, y, phi); UnreachableError names the leg that cannot reach.")
      .def("ik_all", &ik_all, py::arg("pose"), "(8, 3): row k for mode k of RRR3.modes, NaN where unreachable.")
      .def("ik_batch", &ik_batch, py::arg("poses"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "(N, 3) actuated angles for (N, 3) poses, NaN rows where a leg cannot reach (GIL released).")
      .def("ik_newton", &ik_newton, py::arg("pose"), py::arg("guess"), py::arg("max_iter") = kNewtonMaxIter,
           py::arg("tol") = kNewtonTol, "Newton-Raphson on the 6 loop equations from guess (alpha, beta).")
      .def("fk", &fk, py::arg("alpha"), py::arg("guess"), py::arg("max_iter") = kNewtonMaxIter, py::arg("tol") = kNewtonTol,
           "One assembly mode by Newton from a guess pose.")
      .def("fk_all", &fk_all, py::arg("alpha"),
           "(k, 3) every assembly mode, k <= 6, sorted by phi; each once (a double root at a parallel\n"
           "singularity too; modes closer than the loops can tell in floating point, some 1e-7 of the\n"
           "size, as one). Where the elbows form a triangle congruent to the platform's (e.g. equal\n"
           "alpha_i when base_radius == platform_radius) the platform also moves on a continuum (phi\n"
           "fixed, E on a circle of radius l2): those poses are not returned, only the isolated modes.")
      .def("points", &points, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "Joint positions for drawing: dict of (3, 2) arrays 'O', 'A', 'B'.")
      .def("jacobians", &jacobians, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode),
           "The seed's (A, B), A v = B alpha_dot with v = (v_x, v_y, w) in the effector frame.")
      .def("singularity", [](const RRR3& r, ArrayLike pose, ModeLike mode, double tol) {
        return r.singularity(as_pose(pose), as_mode(mode), tol);
      }, py::arg("pose"), py::arg("mode") = FieldCodec<Mode>::to_python(kDefaultMode), py::arg("tol") = kSingularTol,
           "Classification with tol on the normalised determinants.");
}

// RRR3's workspace and planning (plan, connect, plan_loop).
void def_planning(py::class_<RRR3>& cls) {
  // Docstrings that list the options with their defaults (kept for the module's lifetime).
  static const std::string plan_doc =
      keyword_list<RRR3PlanOptions>("plan(points, *") + "\n\n"
      "Poses to follow (K, 2) points at nominal orientation phi, leaving it only near parallel singularities;\n"
      "options keyword-only (RRR3PlanOptions).";
  static const std::string connect_doc =
      keyword_list<RRR3ConnectOptions>("connect(start, goal, *") + "\n\n"
      "Poses from start to goal along which det A keeps its sign and the distance to parallel\n"
      "singularities stays >= clearance (less only where an end is itself nearer); NoRouteError says\n"
      "why there is none (the two poses are in different singularity-free regions of the mode);\n"
      "options keyword-only (RRR3ConnectOptions).";
  static const char* loop_doc =
      "plan_loop(points, *, sign=1, nominals=RRR3LoopOptions().nominals, **plan options but phi and closed)\n\n"
      "The closed plan (K, 2) points about the first of nominals whose plan keeps det A of sign all\n"
      "along (with avoid: clear of parallel singularities by margin); RRR3Loop says which nominal, or\n"
      "why none ('start', 'plan'). Options keyword-only (RRR3LoopOptions, RRR3PlanOptions).";
  static const std::string workspace_doc =
      keyword_list<RRR3WorkspaceOptions>("workspace(*") + "\n\n"
      "Constant-orientation workspace on an n x n grid with singular cells (every core); options\n"
      "keyword-only (RRR3WorkspaceOptions).";
  cls.def("workspace", &workspace_map, workspace_doc.c_str())
      .def("plan", &plan, py::arg("points"), plan_doc.c_str())
      .def("connect", &connect_poses, py::arg("start"), py::arg("goal"), connect_doc.c_str())
      .def("plan_loop", &loop_plan, py::arg("points"), loop_doc);
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
      .def("__repr__", [](const RRR3& r) {
        return "RRR3(base_radius=" + exact_number(r.base_radius()) + ", platform_radius=" +
               exact_number(r.platform_radius()) + ", l1=" + exact_number(r.l1()) + ", l2=" + exact_number(r.l2()) + ")";
      });
}

}  // namespace

void bind_rrr3(py::module_& m) {
  register_errors();
  bind_kinematics_results(m);
  bind_plan_results(m);
  bind_workspace_result(m);
  bind_options(m);
  bind_defaults(m);
  bind_design_study(m);
  py::class_<RRR3> cls(m, "RRR3", "The planar 3-RRR parallel robot (the 3-RRR project, geometry of DESIGN.md).");
  def_geometry(cls);
  def_kinematics(cls);
  def_planning(cls);
  def_value(cls);
}

}  // namespace robokin::bind
