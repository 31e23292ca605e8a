// robokin.RRR3: the planar 3-RRR parallel robot of the 3-RRR project, its inverse and forward
// models, Jacobians and singularities, its planners (plan, plan_loop, connect) and workspace, their
// options and results, and the design study's areas.
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
#include <string>

namespace robokin::bind {
namespace {

// The working mode: 3 signs (m_0, m_1, m_2) of +-1.
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

using Elbows = Eigen::Matrix<double, 3, 2>;

py::array_t<double> ik_batch(const RRR3& r, ArrayLike poses_obj, ModeLike mode_obj, OutArray out_obj) {
  const Mode mode = as_mode(mode_obj);
  const Array poses = rows_arg(poses_obj, "poses", {3}, "N");
  const long n = static_cast<long>(poses.shape(0));
  const py::ssize_t shape[2] = {n, 3};
  const py::array given = output_array(out_obj, 2, shape, poses.data(), poses.size(), "poses");
  const auto out = py::reinterpret_borrow<py::array_t<double>>(given);  // float64, as output_array checked
  double* dst = float64_data(out);
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
           py::kw_only(), py::arg("out") = py::none(),
           "(N, 3) actuated angles for (N, 3) poses in working mode mode, NaN rows where a leg cannot\n"
           "reach (GIL released). out: an (N, 3) array to write them into (returned), for repeated calls.")
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

RRR3Plan plan(const RRR3& r, ArrayLike points_obj, const py::kwargs& kwargs) {
  const Array pts = rows_arg(points_obj, "points", {2});
  const auto o = options_arg<RRR3PlanOptions>(kwargs);
  const long count = static_cast<long>(pts.shape(0));
  // The sizes (grid memory, work of the dynamic programme) are bounded by plan_path itself.
  return released("RRR3.plan", [&](Progress* progress) { return plan_path(r, pts.data(), count, o, progress); });
}

// plan_loop(points, **kwargs): the loop's own options (sign, nominals) and the plan's (all but phi,
// searched, and closed, always true).
RRR3Loop loop_plan(const RRR3& r, ArrayLike points_obj, const py::kwargs& kwargs) {
  const Array pts = rows_arg(points_obj, "points", {2});
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
  const auto loop = options_arg<RRR3LoopOptions>(loop_kwargs);
  const auto o = options_arg<RRR3PlanOptions>(plan_kwargs);
  const long count = static_cast<long>(pts.shape(0));
  return released("RRR3.plan_loop",
                  [&](Progress* progress) { return plan_loop(r, pts.data(), count, o, loop, progress); });
}

RRR3Plan connect_poses(const RRR3& r, ArrayLike start_obj, ArrayLike goal_obj, const py::kwargs& kwargs) {
  const Pose start = as_pose(start_obj, "start"), goal = as_pose(goal_obj, "goal");
  const auto o = options_arg<RRR3ConnectOptions>(kwargs);
  return released("RRR3.connect", [&](Progress* progress) { return connect(r, start, goal, o, progress); });
}

RRR3Workspace workspace_map(const RRR3& r, const py::kwargs& kwargs) {
  const RRR3WorkspaceOptions o = options_arg<RRR3WorkspaceOptions>(kwargs);
  return released("RRR3.workspace", [&](Progress* progress) { return workspace(r, o, progress); });
}

py::array_t<double> rrr3_region_areas(ArrayLike robots_obj, const py::kwargs& kwargs) {
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
  const RRR3WorkspaceOptions o = options_arg<RRR3WorkspaceOptions>(kwargs);
  const std::vector<double> areas =
      released("design study", [&](Progress* progress) { return region_areas(robots, o, progress); });
  return array_of(areas.data(), {static_cast<py::ssize_t>(areas.size())});
}

// The answers of plan, connect and plan_loop.
void bind_plan_results(py::module_& m) {
  ResultClass<RRR3Plan>(m, "RRR3Plan", "Answer of RRR3.plan and RRR3.connect: the poses to follow and what they give.", false)
      .fields()
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
py::array_t<std::uint8_t> workspace_cells(const RRR3Workspace& w) { return array_of(w.cells.data(), {w.n, w.n}); }

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
        def_kept(cls, "x", [](const RRR3Workspace& w) { return to_numpy(w.x()); }, "Cell centres along x (n,).");
        def_kept(cls, "y", [](const RRR3Workspace& w) { return to_numpy(w.y()); }, "Cell centres along y (n,).");
        cls.def_property_readonly("extent", [](const RRR3Workspace& w) { return py::tuple(py::cast(w.extent())); },
                                   "(x_min, x_max, y_min, y_max) of the grid, for matplotlib's imshow.");
      });
}

// The options structs of plan, workspace, connect and plan_loop, from their headers' field lists.
void bind_options(py::module_& m) {
  OptionsClass<RRR3PlanOptions>(m, "RRR3PlanOptions", "The options of RRR3.plan (keywords); defaults as in the seed's simulator.").fields();
  OptionsClass<RRR3WorkspaceOptions>(m, "RRR3WorkspaceOptions", "The options of RRR3.workspace (its arguments, one map's).").fields();
  OptionsClass<RRR3ConnectOptions>(m, "RRR3ConnectOptions", "The options of RRR3.connect (keywords).").fields();
  OptionsClass<RRR3LoopOptions>(m, "RRR3LoopOptions", "The options of RRR3.plan_loop of its own (keywords); the plan's are RRR3PlanOptions'.")
      .fields();
}

// rrr3_region_areas: the design study's areas (robokin.rrr3_design).
void bind_design_study(py::module_& m) {
  static const std::string doc = kwargs_doc<RRR3WorkspaceOptions>(
      "rrr3_region_areas(robots, *",
      "RRR3Workspace.area for each row (base_radius, platform_radius, l1, l2) of robots, on the maps of the\n"
      "options. Use robokin.rrr3_design.");
  m.def("rrr3_region_areas", &rrr3_region_areas, py::arg("robots"), doc.c_str());
}

// RRR3's workspace and planning (plan, connect, plan_loop).
void def_planning(py::module_& m, py::class_<RRR3>& cls) {
  bind_plan_results(m);
  bind_workspace_result(m);
  bind_options(m);
  bind_design_study(m);
  // Docstrings that list the options with their defaults and docs (kept for the module's lifetime).
  static const std::string plan_doc = kwargs_doc<RRR3PlanOptions>(
      "plan(points, *",
      "Poses to follow (K, 2) points at nominal orientation phi, leaving it only near parallel singularities.");
  static const std::string connect_doc = kwargs_doc<RRR3ConnectOptions>(
      "connect(start, goal, *",
      "Poses from start to goal along which det A keeps its sign and the distance to parallel\n"
      "singularities stays >= clearance (less only where an end is itself nearer); NoRouteError says\n"
      "why there is none (the two poses are in different singularity-free regions of the mode).");
  static const std::string loop_doc = kwargs_doc<RRR3LoopOptions>(
      "plan_loop(points, *",
      "The closed plan (K, 2) points about the first of nominals whose plan keeps det A of sign all\n"
      "along (with avoid: clear of parallel singularities by margin); RRR3Loop says which nominal, or\n"
      "why none ('start', 'plan'). It takes the plan's options too, but phi (searched over nominals)\n"
      "and closed (always true).") + "\n\n" + options_doc<RRR3PlanOptions>();
  static const std::string workspace_doc = kwargs_doc<RRR3WorkspaceOptions>(
      "workspace(*", "Constant-orientation workspace on an n x n grid with singular cells (every core).");
  cls.def("workspace", &workspace_map, workspace_doc.c_str())
      .def("plan", &plan, py::arg("points"), plan_doc.c_str())
      .def("connect", &connect_poses, py::arg("start"), py::arg("goal"), connect_doc.c_str())
      .def("plan_loop", &loop_plan, py::arg("points"), loop_doc.c_str());
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
  def_planning(m, cls);
  def_value(cls);
}

}  // namespace robokin::bind
