// robokin.RRR3 is bound in two parts: the robot and its models (rrr3.cpp, which makes the class)
// and its planners and workspace (rrr3_planning.cpp). What both read from Python is here.
#pragma once

#include "arrays.hpp"
#include "options.hpp"

#include "robokin/rrr3.hpp"

#include <cmath>
#include <string>

namespace robokin::bind {

// The working mode: 3 signs (m_0, m_1, m_2) of +-1.
inline Mode as_mode(py::handle obj) {
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

// The working mode as an options field: a tuple of signs in Python.
template <>
struct FieldCodec<Mode> {
  static constexpr bool defined = true;
  using Arg = ModeLike;
  static std::string kind() { return "(m_0, m_1, m_2) of +-1"; }
  static py::tuple to_python(const Mode& m) { return py::make_tuple(m[0], m[1], m[2]); }
  static Mode from_python(py::handle obj, const char*) { return as_mode(obj); }
};

// A finite pose (x, y, phi) with |x|, |y| <= 1e100 m: squared distances to it stay finite, so the
// closure errors of ik_newton and fk do (ik_batch gives NaN rows for any farther pose).
inline Pose as_pose(py::handle obj, const char* name = "pose") {
  const Pose p = as_vector(obj, name, 3);
  if (!(std::abs(p(0)) <= 1e100 && std::abs(p(1)) <= 1e100)) fail(std::string(name) + ": x and y must be within 1e100 m");
  return p;
}

// rrr3_planning.cpp: plan, plan_loop, connect, workspace, the design study, their options and results.
void def_rrr3_planning(py::module_& m, py::class_<RRR3>& cls);

}  // namespace robokin::bind
