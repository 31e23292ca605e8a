// Arguments of the Chain methods (chain.cpp) and the closed forms: joint
// configurations, one (dof,) or a batch (N, dof), checked once, read in place when already
// C-contiguous float64; task names; joint limits.
#pragma once

#include "arrays.hpp"
#include "options.hpp"

#include "robokin/chain.hpp"
#include "robokin/limits.hpp"
#include "robokin/reach.hpp"
#include "robokin/task.hpp"

#include <string>
#include <utility>
#include <vector>

namespace robokin::bind {

// q of shape (dof,) or (N, dof), finite (unless `finite` is false: a caller that checks the values
// itself, as the batch FK does in its kernel). Returns N, or -1 for a single configuration.
inline long check_q(const Chain& c, const Float64View& q, const char* name = "q", bool finite = true) {
  return one_or_batch(q, name, c.dof(), finite);
}

// Finite q can still give an overflowing result (lengths or prismatic joints near 1e308): a
// ValueError naming q rather than inf or NaN in the answer.
inline void require_finite_result(const double* data, py::ssize_t size, const char* name = "q") {
  if (!all_finite(data, size))
    fail(std::string(name) + ": the result is not finite (the joint values or the chain's lengths are too large)");
}

// q as a float64 view: the array itself when it already is C-contiguous float64 (the fast path:
// nothing converted, nothing allocated), else a converted copy that the view keeps alive.
struct QView : Float64View {
  py::object holder;  // the converted copy, when one was made (null otherwise: no empty array made)
  explicit QView(py::handle q_obj) {
    if (float64_view(q_obj, *this)) return;
    const Array a = as_array(q_obj, "q");
    holder = a;
    static_cast<Float64View&>(*this) = view_of(a);
  }
};

// The task named by obj (a string), or for None the chain's natural task (natural_task, task.hpp).
inline Task task_of(py::handle obj, const Chain& chain) {
  if (obj.is_none()) return natural_task(chain);
  if (PyUnicode_Check(obj.ptr())) {
    Py_ssize_t len = 0;
    const char* s = PyUnicode_AsUTF8AndSize(obj.ptr(), &len);
    if (!s) throw py::error_already_set();
    return parse_task(std::string(s, static_cast<size_t>(len)));  // short: no allocation; throws naming the task
  }
  // Not a string: a TypeError, as pybind11 raised when the argument was typed std::string.
  throw py::type_error("task: expected None or a string, one of 'pose', 'position', 'xy', 'xyphi'");
}

// The null-space gains of a Reach or resolved-rate call (reach.hpp): None for none, "joint_limits"
// for the seed's joint-limit avoidance (joint_limit_gains), or (dof,) gains.
inline Vector nullspace_gains(const Chain& chain, py::handle nullspace) {
  if (nullspace.is_none()) return Vector();
  if (py::isinstance<py::str>(nullspace)) {
    if (py::cast<std::string>(nullspace) != "joint_limits")
      fail("nullspace: expected None, 'joint_limits' or an array of gains, got '" + py::cast<std::string>(nullspace) +
           "'");
    return joint_limit_gains(chain);
  }
  return as_vector(nullspace, "nullspace", chain.dof());
}

// The options of a Reach, tracking or resolved-rate call: its keyword arguments, plus the null-space
// gains its `nullspace` argument gives for the chain; validated against the chain.
template <class Options>
Options options_with_nullspace(const Chain& chain, const py::kwargs& kwargs, py::handle nullspace) {
  Options o = options_arg<Options>(kwargs);
  o.nullspace_gains = nullspace_gains(chain, nullspace);
  o.validate(chain);
  return o;
}

// Joint limits: None (none), or a pair (lower, upper) of arrays of dof values (any equal sizes for
// dof < 0, which the Chain constructor checks), checked by the core's validate_limits.
inline JointLimits limits_arg(py::handle obj, int dof, std::vector<bool> prismatic = {}) {
  JointLimits lim;
  lim.prismatic = std::move(prismatic);
  if (obj.is_none()) return lim;
  // A 0-d array is a sequence without a length: PyObject_Length fails (-1), which is cleared here.
  const Py_ssize_t size = py::isinstance<py::sequence>(obj) ? PyObject_Length(obj.ptr()) : -1;
  if (size < 0) PyErr_Clear();
  if (py::isinstance<py::str>(obj) || size < 0) fail_kind("limits: expected None or a pair (lower, upper) of arrays");
  if (size != 2) fail("limits: expected None or a pair (lower, upper) of arrays");
  const py::sequence pair = py::reinterpret_borrow<py::sequence>(obj);
  lim.lower = as_vector(pair[0], "limits", dof, false);
  lim.upper = as_vector(pair[1], "limits", dof, false);
  if (dof >= 0) validate_limits(dof, lim.lower, lim.upper);
  return lim;
}

// The limits of a closed form bound to a chain: "default" for the chain's own, read in place (none
// when it has not dof joints), else as limits_arg, held in `given` (the caller's, which outlives
// the reference returned).
inline const JointLimits& limits_or_default(const Chain& chain, py::handle obj, int dof, JointLimits& given) {
  if (!py::isinstance<py::str>(obj)) return given = limits_arg(obj, dof);
  if (PyUnicode_CompareWithASCIIString(obj.ptr(), "default") != 0)
    fail("limits: expected 'default', None or a pair (lower, upper)");
  return chain.dof() == dof ? chain.limits() : given;
}

}  // namespace robokin::bind
