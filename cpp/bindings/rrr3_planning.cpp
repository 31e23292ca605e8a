// robokin.RRR3's planners and workspace (plan, plan_loop, connect, workspace), their options and
// results, and the design study's areas: the second part of the RRR3 class (rrr3_parts.hpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"
#include "rrr3_parts.hpp"

#include "robokin/rrr3_connect.hpp"
#include "robokin/rrr3_loop.hpp"
#include "robokin/rrr3_plan.hpp"
#include "robokin/rrr3_workspace.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <optional>

namespace robokin::bind {
namespace {

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
  m.def("rrr3_region_areas", &study_areas, py::arg("robots"), doc.c_str());
}

}  // namespace

// RRR3's workspace and planning (plan, connect, plan_loop).
void def_rrr3_planning(py::module_& m, py::class_<RRR3>& cls) {
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


}  // namespace robokin::bind
