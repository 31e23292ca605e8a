// robokin.Chain: serial chains from DH tables or plain segments, FK, Jacobians, frames,
// manipulability; joint and link names; pickling, ==, hash. Text for people, and the constructors'
// and q_from's reading of Python's values, are written in Python (robokin._printing, _chain, _urdf).
// fk, jacobian and manipulability are fast methods (internals.hpp), declared in one table here: the
// Chain methods whose every call is cheap, so that pybind11's dispatcher would be a large part of
// it. A method is kept there only while its gain over a pybind11 .def of the same function is 10 %
// or more (benchmarks/README.md says how it was measured).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "progress.hpp"

#include "robokin/chain.hpp"
#include "robokin/manipulability.hpp"
#include "robokin/task.hpp"

#include <pybind11/stl.h>
#include <pybind11/typing.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace robokin::bind {
namespace {

Matrix4 optional_tool(py::handle tool) {
  return tool.is_none() ? Matrix4::Identity() : Matrix4(as_transform(tool, "tool"));
}

// Chain.from_dh's and from_segments' core (robokin._chain reads and checks the records: their kinds,
// shapes and finiteness); the frames (a tip, the tool) and the limits are checked here.
// One letter of `allowed` per row of a `rows`-row table (checked here as well: these calls are
// reachable from Python with arrays of any size).
void require_letters(const std::string& letters, const char* allowed, py::ssize_t rows, const char* name) {
  if (static_cast<py::ssize_t>(letters.size()) != rows || letters.find_first_not_of(allowed) != std::string::npos)
    fail(std::string(name) + ": expected one of " + allowed + " per row (" + std::to_string(rows) + ")");
}

Chain chain_from_dh(ArrayLike table, const std::string& joints, bool modified, OptionalArrayLike tool,
                    LimitsLike limits) {
  const Array t = rows_arg(table, "rows", {4});
  require_letters(joints, "RP", t.shape(0), "joints");
  std::vector<DHRow> rows;
  for (size_t i = 0; i < joints.size(); ++i) {
    const double* r = t.data() + 4 * i;
    rows.push_back(DHRow{r[0], r[1], r[2], r[3], joints[i] == 'P'});
  }
  const JointLimits lim = limits_arg(limits, -1);
  return Chain::from_dh(rows, modified, optional_tool(tool), lim.lower, lim.upper);
}

Chain chain_from_segments(const std::string& types, ArrayLike axes, ArrayLike tips, OptionalArrayLike tool,
                          LimitsLike limits) {
  const Array a = rows_arg(axes, "segments", {3}), t = rows_arg(tips, "segments", {4, 4});
  require_letters(types, "RPF", a.shape(0), "types");
  require_letters(types, "RPF", t.shape(0), "types");
  std::vector<SegmentSpec> specs(types.size());
  for (size_t i = 0; i < types.size(); ++i) {
    SegmentSpec& spec = specs[i];
    spec.type = types[i] == 'R' ? JointType::Revolute : types[i] == 'P' ? JointType::Prismatic : JointType::Fixed;
    spec.axis = Eigen::Map<const Eigen::Vector3d>(a.data() + 3 * i).normalized();
    if (!(spec.axis.norm() > 0.5))  // zero (or too large to normalise): robokin._chain scales it first
      fail("segments[" + std::to_string(i) + "] axis: must not be zero");
    spec.tip = rigid_at(t.data() + 16 * i, ("segments[" + std::to_string(i) + "] tip").c_str());
  }
  const JointLimits lim = limits_arg(limits, -1);
  return Chain::from_segments(specs, optional_tool(tool), lim.lower, lim.upper);
}

Vector single_q(const Chain& c, py::handle obj, const char* name = "q") {
  return as_vector(obj, name, c.dof());
}

// fk's `part`: "frame" (4 x 4 per configuration, the default) or "position" (the tool point, 3 values).
FkOutput fk_part_of(py::handle obj) {
  if (!PyUnicode_Check(obj.ptr()))
    throw py::type_error("part: expected the string 'frame' or 'position', got " +
                         std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  // Compared in place: no std::string made per call (fk is called in loops).
  if (PyUnicode_CompareWithASCIIString(obj.ptr(), "frame") == 0) return FkOutput::Frame;
  if (PyUnicode_CompareWithASCIIString(obj.ptr(), "position") == 0) return FkOutput::Position;
  fail("part: expected 'frame' or 'position', got '" + py::cast<std::string>(obj) + "'");
}

// Chain.fk and Chain.jacobian, bound as fast methods (the table below).
py::array chain_fk(const Chain& c, ArrayLike q_obj, FkPart part_obj, OutArray out_obj) {
  const FkOutput what = fk_part_of(part_obj);
  const int width = what == FkOutput::Position ? 3 : 16;
  const QView q(q_obj);
  // A batch's joint values are checked by the core as it reads them (Chain::fk_batch).
  const long count = check_q(c, q, "q", false);
  if (count < 0) {
    require_finite(q.data, q.size, "q");
    Rigid T;
    c.fk(q.data, T);
    const py::ssize_t frame_shape[2] = {4, 4}, position_shape[1] = {3};
    py::array out = what == FkOutput::Position ? output_array(out_obj, 1, position_shape, q.data, q.size)
                                               : output_array(out_obj, 2, frame_shape, q.data, q.size);
    double* m = float64_data(out);
    if (what == FkOutput::Position) m[0] = T.p(0), m[1] = T.p(1), m[2] = T.p(2);
    else write_frame(T, m);
    require_finite_result(m, width);
    return out;
  }
  const py::ssize_t frame_shape[3] = {count, 4, 4}, position_shape[2] = {count, 3};
  py::array out = what == FkOutput::Position ? output_array(out_obj, 2, position_shape, q.data, q.size)
                                             : output_array(out_obj, 3, frame_shape, q.data, q.size);
  double* dst = float64_data(out);
  const bool finite =
      released("Chain.fk", [&](Progress* progress) { return c.fk_batch(q.data, count, dst, what, progress); });
  if (!finite) {  // the same errors, in the same order, as when q was checked first
    require_finite(q.data, q.size, "q");
    require_finite_result(dst, width * count);
  }
  return out;
}

py::array chain_jacobian(const Chain& c, ArrayLike q_obj, TaskName task_obj, OutArray out_obj) {
  const Task task = task_of(task_obj, c);
  const QView q(q_obj);
  const long count = check_q(c, q);
  const int rows = task_rows(task), n = c.dof();
  const int* row_of = task_row_indices(task);
  const long batch = count < 0 ? 1 : count;
  py::array out = count < 0 ? output_array(out_obj, 2, std::array<py::ssize_t, 2>{rows, n}.data(), q.data, q.size)
                            : output_array(out_obj, 3, std::array<py::ssize_t, 3>{batch, rows, n}.data(), q.data, q.size);
  double* dst = float64_data(out);
  // The 6 x n Jacobian (column-major) on the stack for the usual sizes.
  double small[6 * 16];
  std::vector<double> large(n > 16 ? 6 * n : 0);
  double* J = n > 16 ? large.data() : small;
  Rigid T;
  for (long k = 0; k < batch; ++k, dst += rows * n) {
    c.fk_jacobian(q.data + k * n, T, J);
    for (int r = 0; r < rows; ++r)
      for (int j = 0; j < n; ++j) dst[r * n + j] = J[6 * j + row_of[r]];
  }
  require_finite_result(float64_data(out), batch * rows * n);
  return out;
}

py::array_t<double> frames(const Chain& c, ArrayLike q_obj) {
  const std::vector<Matrix4> f = c.frames(single_q(c, q_obj));
  py::array_t<double> out = new_array({static_cast<py::ssize_t>(f.size()), 4, 4});
  for (size_t i = 0; i < f.size(); ++i)
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(out.mutable_data() + 16 * i) = f[i];
  require_finite_result(out.data(), out.size());
  return out;
}

py::array_t<double> point_in_frame(const Chain& c, ArrayLike q_obj, ArrayLike point_obj, long frame,
                                   long in_frame) {
  const Vector q = single_q(c, q_obj);
  const Vector p = as_vector(point_obj, "point", 3);
  const long last = c.dof();  // frames: the base and one after each joint
  if (frame < 0 || frame > last) fail("frame: expected 0.." + std::to_string(last) + ", got " + std::to_string(frame));
  if (in_frame < 0 || in_frame > last)
    fail("in_frame: expected 0.." + std::to_string(last) + ", got " + std::to_string(in_frame));
  const Eigen::VectorXd out = c.point_in_frame(q, p, static_cast<int>(frame), static_cast<int>(in_frame));
  require_finite_result(out.data(), 3, "q, point");
  return to_numpy(out);
}

std::string joint_types(const Chain& c) {
  std::string s;
  for (int i = 0; i < c.dof(); ++i) s += c.prismatic(i) ? 'P' : 'R';
  return s;
}

void def_chain_model(py::class_<Chain>& chain) {
  chain
      .def_property_readonly("dof", &Chain::dof, "Number of joints.")
      .def_property_readonly("joint_types", &joint_types, "One letter per joint: 'R' revolute, 'P' prismatic.")
      .def_property_readonly(
          "natural_task", [](const Chain& c) { return task_name(natural_task(c)); },
          "The task calls control when given task=None: 'xyphi' for a planar arm (every joint moving the tool\n"
          "parallel to the base xy plane) with at least three revolute joints, 'xy' for another planar arm,\n"
          "'pose' for a spatial arm of six joints or more, 'position' for one with fewer.")
      .def_property_readonly(
          "limits", [](const Chain& c) { return py::make_tuple(to_numpy(c.lower()), to_numpy(c.upper())); },
          "(lower, upper) joint limits; +-inf where a joint is unlimited.")
      .def("frames", &frames, py::arg("q"),
           "Frames (dof + 1, 4, 4) at q (dof,), in the base frame: frames[0] the base (the identity), frames[i]\n"
           "the frame after joint i (for a DH chain A_1 ... A_i), frames[dof] the last with the tool applied (so\n"
           "frames[dof] == fk(q)). Fixed segments between joints belong to the frame after the joint before them.")
      .def("point_in_frame", &point_in_frame, py::arg("q"), py::arg("point"), py::arg("frame"),
           py::arg("in_frame") = 0,
           "Expresses a point given in one frame of the chain in another, at q (dof,): point (3,) in frame\n"
           "`frame`, returned (3,) in frame `in_frame` (default 0, the base). Frames are numbered as\n"
           "Chain.frames numbers them: 0 the base, i the frame after joint i, dof the last with the tool.")
      .def("_fk_kdl", [](const Chain& c, ArrayLike q) { return to_numpy(c.fk_kdl(single_q(c, q))); },
           py::arg("q"), "Reference: KDL's ChainFkSolverPos_recursive.")
      .def("_jacobian_kdl", [](const Chain& c, ArrayLike q) { return to_numpy(c.jacobian_kdl(single_q(c, q))); },
           py::arg("q"), "Reference: KDL's ChainJntToJacSolver (6 x dof).");
}

Measure measure_of(py::handle obj) {
  if (!PyUnicode_Check(obj.ptr()))
    throw py::type_error("measure: expected a string, one of 'yoshikawa', 'condition', 'min_singular'");
  Py_ssize_t len = 0;
  const char* s = PyUnicode_AsUTF8AndSize(obj.ptr(), &len);
  if (!s) throw py::error_already_set();
  return parse_measure(std::string(s, static_cast<size_t>(len)));  // std::invalid_argument -> ValueError
}

// Chain.manipulability, bound as a fast method (the table below).
py::object chain_manipulability(const Chain& c, ArrayLike q_obj, MeasureName measure_obj, TaskName task_obj,
                                 OutArray out_obj) {
  const Measure measure = measure_of(measure_obj);
  const Task task = task_of(task_obj, c);
  const QView q(q_obj);
  const long count = check_q(c, q);
  if (count < 0) {
    if (!out_obj.is_none()) fail("out: a single q gives a float; out is for a batch q (N, dof)");
    const double v = robokin::manipulability(c, q.data, task, measure);
    require_finite_result(&v, 1);
    return py::float_(v);
  }
  const py::ssize_t shape[1] = {count};
  py::array out = output_array(out_obj, 1, shape, q.data, q.size);
  double* dst = float64_data(out);
  released("Chain.manipulability",
           [&](Progress* progress) { manipulability_batch(c, q.data, count, task, measure, dst, progress); });
  require_finite_result(dst, count);
  return std::move(out);
}

py::tuple ellipsoid(const Chain& c, ArrayLike q_obj, const std::string& part) {
  if (part != "translation" && part != "rotation")
    fail("part: expected 'translation' or 'rotation', got '" + part + "'");
  const Vector q = as_vector(q_obj, "q", c.dof());
  Eigen::Matrix3d axes;
  Eigen::Vector3d lengths;
  robokin::ellipsoid(c, q.data(), part == "rotation", axes, lengths);
  require_finite_result(lengths.data(), 3);
  require_finite_result(axes.data(), 9);
  return py::make_tuple(to_numpy(axes), to_numpy(Eigen::VectorXd(lengths)));
}

void def_chain_manipulability(py::class_<Chain>& cls) {
  cls.def("ellipsoid", &ellipsoid, py::arg("q"), py::arg("part") = "translation",
      "Velocity ellipsoid of the translational (part 'translation': rows v) or rotational ('rotation':\n"
      "rows w) Jacobian at q: (axes, lengths), axes (3, 3) unit columns in the base frame (a right-handed\n"
      "frame), lengths (3,) the singular values in decreasing order (0 for missing directions).");
}

using Names = py::typing::Tuple<py::str, py::ellipsis>;

Names as_tuple(const std::vector<std::string>& names) {
  Names t(names.size());
  for (size_t i = 0; i < names.size(); ++i) t[i] = py::str(names[i]);
  return t;
}

void def_chain_names(py::class_<Chain>& cls) {
  cls.def_property_readonly(
      "joint_names", [](const Chain& c) { return as_tuple(c.joint_names()); },
      "The names of the dof joints, in q's order: a URDF chain's from the file (its movable joints\n"
      "between base and tip); q1 .. qn for a chain from a DH table or plain segments.");
  cls.def_property_readonly(
      "link_names", [](const Chain& c) { return as_tuple(c.link_names()); },
      "The names of the dof + 1 links whose frames frames(q) gives: the base link, the link each of\n"
      "joints 1 .. dof-1 moves, and the chain's last link (the tip, after any fixed joints: a flange,\n"
      "tool0). A URDF chain's are the file's; base, link1 .. linkn for a DH or segment chain.");
}

// Version 2 added the base link's name to the "segments" layout; version 1 states still load.
constexpr int kChainStateVersion = 2;

py::tuple floats(const double* v, int count) {
  py::tuple t(count);
  for (int i = 0; i < count; ++i) t[i] = py::float_(v[i]);
  return t;
}

using RowMajor4 = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;

py::tuple matrix_rows(const Matrix4& m) { return floats(RowMajor4(m).data(), 16); }

// A state entry of `count` floats (exact: Python floats are doubles).
std::vector<double> floats_of(py::handle obj, size_t count, const char* what) {
  std::vector<double> v;
  try {
    v = py::cast<std::vector<double>>(obj);
  } catch (const py::cast_error&) {
    fail(std::string("Chain state: ") + what + " is not a sequence of numbers");
  }
  if (count && v.size() != count)
    fail(std::string("Chain state: ") + what + " has " + std::to_string(v.size()) + " numbers, expected " +
         std::to_string(count));
  return v;
}

Matrix4 matrix_of(py::handle obj, const char* what) {
  return Eigen::Map<const RowMajor4>(floats_of(obj, 16, what).data());
}

Vector vector_of(py::handle obj, const char* what) {
  const std::vector<double> v = floats_of(obj, 0, what);
  return Eigen::Map<const Vector>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// ("robokin.Chain", version, "dh", rows, modified, tool, lower, upper) for a chain built from a DH
// table, ("robokin.Chain", version, "segments", records, lower, upper, base link name) otherwise
// (version 1: without the base link's name); a record is (segment name, joint name, KDL joint
// type, origin (3), axis (3), tip (16, row-major)).
py::tuple chain_state(const Chain& c) {
  const py::tuple lower = floats(c.lower().data(), c.dof()), upper = floats(c.upper().data(), c.dof());
  if (const DHTable* dh = c.dh()) {
    py::list rows;
    for (const DHRow& r : dh->rows)
      rows.append(py::make_tuple(r.a, r.alpha, r.d, r.theta, r.prismatic ? "P" : "R"));
    return py::make_tuple("robokin.Chain", kChainStateVersion, "dh", py::tuple(rows), dh->modified,
                          matrix_rows(dh->tool), lower, upper);
  }
  py::list records;
  for (const SegmentRecord& r : c.records())
    records.append(py::make_tuple(r.name, r.joint_name, r.type, floats(r.origin.data(), 3), floats(r.axis.data(), 3),
                                  matrix_rows(r.tip)));
  return py::make_tuple("robokin.Chain", kChainStateVersion, "segments", py::tuple(records), lower, upper,
                        c.base_name());
}

Chain chain_from_state(const py::tuple& t) {
  if (t.size() < 3 || !py::isinstance<py::str>(t[0]) || t[0].cast<std::string>() != "robokin.Chain")
    fail("Chain state: not a robokin.Chain state");
  const long version = py::isinstance<py::int_>(t[1]) ? t[1].cast<long>() : -1;
  if (version < 1 || version > kChainStateVersion)
    fail("Chain state: version " + py::repr(t[1]).cast<std::string>() + " is not supported (this robokin reads 1 to " +
         std::to_string(kChainStateVersion) + ")");
  const std::string kind = py::isinstance<py::str>(t[2]) ? t[2].cast<std::string>() : "";
  if (kind == "dh" && t.size() == 8) {
    std::vector<DHRow> rows;
    for (py::handle row : py::reinterpret_borrow<py::sequence>(t[3])) {
      const py::sequence r = py::reinterpret_borrow<py::sequence>(row);
      if (r.size() != 5) fail("Chain state: a DH row is not (a, alpha, d, theta, joint)");
      const std::vector<double> v = floats_of(py::make_tuple(r[0], r[1], r[2], r[3]), 4, "a DH row");
      DHRow d{v[0], v[1], v[2], v[3], py::str(r[4]).cast<std::string>() == "P"};
      rows.push_back(d);
    }
    return Chain::from_dh(rows, t[4].cast<bool>(), matrix_of(t[5], "tool"), vector_of(t[6], "lower"),
                          vector_of(t[7], "upper"));
  }
  const size_t segments_size = version == 1 ? 6 : 7;
  if (kind == "segments" && t.size() == segments_size) {
    std::vector<SegmentRecord> records;
    for (py::handle rec : py::reinterpret_borrow<py::sequence>(t[3])) {
      const py::sequence r = py::reinterpret_borrow<py::sequence>(rec);
      if (r.size() != 6) fail("Chain state: a segment record is not (name, joint, type, origin, axis, tip)");
      SegmentRecord s;
      s.name = py::str(r[0]).cast<std::string>();
      s.joint_name = py::str(r[1]).cast<std::string>();
      s.type = r[2].cast<int>();
      const std::vector<double> o = floats_of(r[3], 3, "a joint origin"), a = floats_of(r[4], 3, "a joint axis");
      s.origin = Eigen::Vector3d(o[0], o[1], o[2]);
      s.axis = Eigen::Vector3d(a[0], a[1], a[2]);
      s.tip = matrix_of(r[5], "a segment tip");
      records.push_back(s);
    }
    const std::string base = version == 1 ? "" : py::str(t[6]).cast<std::string>();
    return Chain::from_records(records, vector_of(t[4], "lower"), vector_of(t[5], "upper"), base);
  }
  fail("Chain state: unknown layout '" + kind + "'");
}

void def_chain_value(py::class_<Chain>& cls) {
  cls.def(py::pickle([](const Chain& c) { return chain_state(c); },
                     [](const py::tuple& t) {
                       try {
                         return chain_from_state(t);
                       } catch (const py::cast_error&) {
                         fail("Chain state: malformed");
                       }
                     }));
  cls.def(
      "__eq__", [](const Chain& a, const Chain& b) { return a.same_kinematics(b); }, py::is_operator(),
      "Same kinematics: joint types, limits and constant frames equal bit for bit (however built).");
  cls.def("__hash__", [](const Chain& c) { return c.kinematics_hash(); });
  // Text for people is written in Python, from the state above.
  cls.def("__repr__", [](py::handle self) {
    return printed("chain_repr", self, self.cast<const Chain&>().named());  // named: a URDF chain's names
  });
  const auto table = [](py::handle self) { return printed("table", self); };
  cls.def("table", table,
          "The kinematic table as text, as print(chain) shows it: a DH chain's rows (a, alpha, d, theta, joint\n"
          "type, lower and upper limits; standard or modified said), any other chain's segments (joint name,\n"
          "type, the frame after the joint at q = 0 as xyz and roll, pitch, yaw, the joint's axis in that\n"
          "frame, limits: a URDF joint's <origin>, <axis> and <limit>). Metres and degrees.");
  cls.def("__str__", table);
}

void def_chain_fast_calls(py::class_<Chain>& cls) {
  const std::string pose = std::string("'") + task_name(Task::Pose) + "'";
  fast_method<&chain_fk>(
      cls, "fk", {{"q", ""}, {"part", "'frame'"}, {"out", "None"}}, 2, "numpy.ndarray",
      "Tool pose (4, 4) for q (dof,); (N, 4, 4) for a batch (N, dof). part='position': the tool\n"
      "point only, (3,) or (N, 3) (the same values as the frames' last column, written alone).\n"
      "out: an array of the result's shape to write it into (returned), for repeated calls.\n");
  fast_method<&chain_jacobian>(
      cls, "jacobian", {{"q", ""}, {"task", pose}, {"out", "None"}}, 2, "numpy.ndarray",
      "Geometric Jacobian at q (dof,) at the tool point in the base frame, rows of the task: (6, dof)\n"
      "by default ('pose': the whole geometric Jacobian), (N, rows, dof) for a batch (N, dof); task\n"
      "None: the chain's natural_task.\n"
      "out: an array of the result's shape to write it into (returned), for repeated calls.\n");
  fast_method<&chain_manipulability>(
      cls, "manipulability", {{"q", ""}, {"measure", "'yoshikawa'"}, {"task", "None"}, {"out", "None"}}, 3,
      "float | numpy.typing.NDArray[numpy.float64]",
      "Manipulability at q by measure, from the singular values of the task's Jacobian rows:\n"
      "'yoshikawa' their product (sqrt(det(J J^T)) when rows <= dof), 'condition' sigma_min /\n"
      "sigma_max (the inverse condition number, 1 isotropic, 0 singular), 'min_singular' sigma_min.\n"
      "A float for q (dof,), an array (N,) for a batch (N, dof) (GIL released, every core). task\n"
      "None: the chain's natural_task (a planar arm's 'pose' rows would always give 0).\n"
      "out: for a batch, an (N,) array to write the values into (returned), for repeated calls.\n");
}

}  // namespace

void bind_chain(py::module_& m) {
  py::class_<Chain> cls(m, "Chain", "A serial kinematic chain (an Orocos KDL chain with joint limits).");
  def_chain_model(cls);
  def_chain_fast_calls(cls);
  def_chain_names(cls);
  def_chain_manipulability(cls);
  def_chain_value(cls);
  m.def("chain_from_dh", &chain_from_dh, py::arg("table"), py::arg("joints"), py::arg("modified"), py::arg("tool"),
        py::arg("limits"), "A chain from DH rows (table (n, 4), joints 'R' / 'P' each). Use Chain.from_dh.");
  m.def("chain_from_segments", &chain_from_segments, py::arg("types"), py::arg("axes"), py::arg("tips"),
        py::arg("tool"), py::arg("limits"),
        "A chain from segments (types 'R' / 'P' / 'F' each, axes (n, 3), tips (n, 4, 4)). Use Chain.from_segments.");
}
}  // namespace robokin::bind
