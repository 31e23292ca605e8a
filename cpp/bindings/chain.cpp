// robokin.Chain: serial chains from DH tables or plain segments; FK, Jacobians, frames.
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_parts.hpp"
#include "chain_args.hpp"
#include "progress.hpp"

#include "robokin/chain.hpp"
#include "robokin/task.hpp"

#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <vector>

namespace robokin::bind {
namespace {

double finite_number(py::handle obj, const std::string& name) {
  double v;
  try {
    v = py::cast<double>(obj);
  } catch (const py::cast_error&) {
    fail(name + ": expected a number");
  }
  if (!std::isfinite(v)) fail(name + ": must be finite");
  return v;
}

std::string joint_letter(py::handle obj, const std::string& name, const char* allowed) {
  if (!py::isinstance<py::str>(obj)) fail(name + ": joint type must be a string, one of " + allowed);
  std::string s = py::cast<std::string>(obj);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.size() != 1 || std::string(allowed).find(s) == std::string::npos)
    fail(name + ": joint type must be one of " + allowed + ", got '" + py::cast<std::string>(obj) + "'");
  return s;
}

// The records of a chain to build (DH rows, segments): `name` a non-empty sequence of sequences of
// `size` items (`what` says which), each read by parse(items, "name[i]") -> Record.
template <class Record, class Parse>
std::vector<Record> records(py::handle obj, const char* name, size_t size, const char* what, Parse parse) {
  if (!py::isinstance<py::sequence>(obj) || py::isinstance<py::str>(obj))
    fail(std::string(name) + ": expected a sequence");
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
  if (seq.size() == 0) fail(std::string(name) + ": a chain needs at least one joint");
  std::vector<Record> out;
  for (size_t i = 0; i < seq.size(); ++i) {
    const std::string item = std::string(name) + "[" + std::to_string(i) + "]";
    const py::object r = seq[i];
    if (!py::isinstance<py::sequence>(r) || py::isinstance<py::str>(r) || py::len(r) != size)
      fail(item + ": expected " + what);
    out.push_back(parse(py::reinterpret_borrow<py::sequence>(r), item));
  }
  return out;
}

Matrix4 optional_tool(py::handle tool) {
  return tool.is_none() ? Matrix4::Identity() : Matrix4(as_transform(tool, "tool"));
}

Chain chain_from_dh(py::handle rows, bool modified, OptionalArrayLike tool, LimitsLike limits) {
  const auto parsed = records<DHRow>(
      rows, "rows", 5, "(a, alpha, d, theta, 'R' or 'P')", [](const py::sequence& r, const std::string& name) {
        // Braced initialisers run in order: the row's first bad value is the one named.
        return DHRow{finite_number(r[0], name + " a"), finite_number(r[1], name + " alpha"),
                     finite_number(r[2], name + " d"), finite_number(r[3], name + " theta"),
                     joint_letter(r[4], name, "RP") == "P"};
      });
  const JointLimits lim = limits_arg(limits, -1);
  return Chain::from_dh(parsed, modified, optional_tool(tool), lim.lower, lim.upper);
}

Chain chain_from_segments(py::handle segments, OptionalArrayLike tool, LimitsLike limits) {
  const auto parsed = records<SegmentSpec>(
      segments, "segments", 3, "(joint type 'R'|'P'|'F', axis (3,), tip (4, 4))",
      [](const py::sequence& s, const std::string& name) {
        SegmentSpec spec;
        const std::string type = joint_letter(s[0], name, "RPF");
        spec.type = type == "R" ? JointType::Revolute : type == "P" ? JointType::Prismatic : JointType::Fixed;
        spec.axis = as_vector(s[1], (name + " axis").c_str(), 3);
        if (spec.axis.norm() < 1e-12) fail(name + " axis: must not be zero");
        spec.axis.normalize();
        spec.tip = as_transform(s[2], (name + " tip").c_str());
        return spec;
      });
  const JointLimits lim = limits_arg(limits, -1);
  return Chain::from_segments(parsed, optional_tool(tool), lim.lower, lim.upper);
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

}  // namespace

// Chain.fk and Chain.jacobian, bound as fast methods (fast_calls.cpp).
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

namespace {

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

}  // namespace

void def_chain_model(py::class_<Chain>& chain) {
  chain
      .def_static("from_dh", &chain_from_dh, py::arg("rows"), py::arg("modified") = false,
                  py::arg("tool") = py::none(), py::arg("limits") = py::none(),
                  "Builds a chain from Denavit-Hartenberg rows.\n\n"
                  "rows: one (a, alpha, d, theta, joint) per joint: a and d in metres, alpha and theta in radians,\n"
                  "joint 'R' (revolute) or 'P' (prismatic). theta and d are offsets: a revolute joint turns by\n"
                  "theta + q_i, a prismatic one slides to d + q_i (q = 0 is the table as written).\n"
                  "modified: False for standard DH, A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha); True for Craig's\n"
                  "modified DH, A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d).\n"
                  "tool: (4, 4) frame of the tool point in the last joint's frame, applied after the last row\n"
                  "(fk, frames and the Jacobian are at the tool); None for the identity.\n"
                  "limits: (lower, upper), each dof numbers (rad or m, -inf / inf for none), or None: unlimited.\n"
                  "print(chain) shows the table (Chain.table).")
      .def_static("from_segments", &chain_from_segments, py::arg("segments"), py::arg("tool") = py::none(),
                  py::arg("limits") = py::none(),
                  "Builds a chain from KDL-style segments, as KDL::Segment(Joint(axis), tip) does.\n\n"
                  "segments: one (joint, axis, tip) per segment: joint 'R' (revolute), 'P' (prismatic) or 'F'\n"
                  "(fixed); axis (3,), not zero, in the segment's starting frame (the joint turns about / slides\n"
                  "along it through that frame's origin); tip the (4, 4) frame that follows the joint. A segment's\n"
                  "frame at q is Rot(axis, q) tip (or Trans(axis * q) tip), so fixed segments only add frames.\n"
                  "tool: (4, 4) frame appended after the last segment; None for the identity.\n"
                  "limits: (lower, upper), each dof numbers (rad or m, -inf / inf for none), or None: unlimited.")
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

void bind_chain(py::module_& m) {
  py::class_<Chain> cls(m, "Chain", "A serial kinematic chain (an Orocos KDL chain with joint limits).");
  def_chain_model(cls);
  def_chain_fast_calls(cls);
  def_chain_names(cls);
  def_chain_from_urdf(cls);
  def_chain_manipulability(cls);
  def_chain_value(cls);
}

}  // namespace robokin::bind
