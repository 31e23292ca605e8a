// Chain.joint_names, Chain.link_names and the conversions between q and {joint name: value}
// (added to the Chain class registered by chain.cpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_parts.hpp"

#include "robokin/chain.hpp"

#include <pybind11/typing.h>

#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

namespace robokin::bind {
namespace {

constexpr char kJointMappingText[] = "collections.abc.Mapping[str, float]";
using JointMapping = Typed<kJointMappingText>;
constexpr char kJointDefaultText[] = "float | numpy.typing.ArrayLike | None";
using JointDefault = Typed<kJointDefaultText>;

constexpr size_t kListedNames = 20;  // an error message lists this many names, then says how many more

// 'a', 'b' and 'c' (the repr of each item); past kListedNames, "... and N more".
std::string listed(const std::vector<py::object>& items) {
  std::string s;
  const size_t shown = std::min(items.size(), kListedNames);
  for (size_t i = 0; i < shown; ++i) {
    const bool last = i + 1 == items.size();
    s += (i == 0 ? "" : last ? " and " : ", ") + py::repr(items[i]).cast<std::string>();
  }
  if (shown < items.size()) s += " and " + std::to_string(items.size() - shown) + " more";
  return s;
}

std::vector<py::object> as_objects(const std::vector<std::string>& names) {
  std::vector<py::object> out;
  for (const std::string& n : names) out.push_back(py::str(n));
  return out;
}

using Names = py::typing::Tuple<py::str, py::ellipsis>;

Names as_tuple(const std::vector<std::string>& names) {
  Names t(names.size());
  for (size_t i = 0; i < names.size(); ++i) t[i] = py::str(names[i]);
  return t;
}

// q (dof,) filled from `default_obj`: a number for every joint, or a (dof,) array; NaN marks "no
// default" (None).
Vector default_q(const Chain& c, py::handle default_obj) {
  if (default_obj.is_none()) return Vector::Constant(c.dof(), NAN);
  const Array a = as_array(default_obj, "default");
  if (a.ndim() == 0) {
    require_finite(a.data(), 1, "default");
    return Vector::Constant(c.dof(), *a.data());
  }
  return as_vector(default_obj, "default", c.dof());
}

double joint_value(py::handle value, const std::string& key) {
  // PyFloat_AsDouble takes what Python's float() takes from a number (ints, numpy scalars,
  // __float__ / __index__); an int past the largest double overflows.
  const bool text = py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value);
  const double v = text ? -1.0 : PyFloat_AsDouble(value.ptr());
  if (text || (v == -1.0 && PyErr_Occurred())) {
    const bool overflow = !text && PyErr_ExceptionMatches(PyExc_OverflowError);
    PyErr_Clear();
    if (overflow) fail("mapping[" + key + "]: must be finite, got an int too large for a float");
    throw py::type_error("mapping[" + key + "]: expected a number, got " +
                         py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  }
  if (!std::isfinite(v)) fail("mapping[" + key + "]: must be finite, got " + py::repr(py::float_(v)).cast<std::string>());
  return v;
}

py::array_t<double> q_from(const Chain& c, JointMapping mapping, JointDefault default_obj) {
  if (!py::isinstance(mapping, py::module_::import("collections.abc").attr("Mapping")))
    throw py::type_error("mapping: expected a mapping {joint name: value}, got " +
                         py::str(py::type::handle_of(mapping).attr("__name__")).cast<std::string>());
  const std::vector<std::string> names = c.joint_names();
  std::unordered_map<std::string, std::vector<int>> index;
  for (int i = 0; i < c.dof(); ++i) index[names[i]].push_back(i);
  Vector q = default_q(c, default_obj);
  std::vector<bool> given(c.dof(), false);
  std::vector<py::object> unknown;
  const py::dict items(py::reinterpret_borrow<py::object>(mapping));
  for (const auto& [key, value] : items) {
    const auto found = py::isinstance<py::str>(key) ? index.find(key.cast<std::string>()) : index.end();
    if (found == index.end()) {
      unknown.push_back(py::reinterpret_borrow<py::object>(key));
      continue;
    }
    const double v = joint_value(value, py::repr(key).cast<std::string>());
    for (int i : found->second) q(i) = v, given[i] = true;
  }
  if (!unknown.empty())
    fail(std::string("mapping: unknown joint name") + (unknown.size() > 1 ? "s " : " ") + listed(unknown) +
         "; the chain's joints are " + listed(as_objects(names)));
  std::vector<py::object> missing;
  for (int i = 0; i < c.dof(); ++i)
    if (!given[i] && std::isnan(q(i))) missing.push_back(py::str(names[i]));
  if (!missing.empty())
    fail(std::string("mapping: no value for joint") + (missing.size() > 1 ? "s " : " ") + listed(missing) +
         " (pass default= for the joints left out)");
  return to_numpy(q);
}

py::typing::Dict<py::str, py::float_> q_dict(const Chain& c, ArrayLike q_obj) {
  const Vector q = as_vector(q_obj, "q", c.dof());
  const std::vector<std::string> names = c.joint_names();
  py::typing::Dict<py::str, py::float_> out;
  for (int i = 0; i < c.dof(); ++i) out[py::str(names[i])] = py::float_(q(i));
  return out;
}

}  // namespace

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
  cls.def("q_from", &q_from, py::arg("mapping"), py::arg("default") = py::none(),
          "q (dof,) from a mapping {joint name: value} (names as joint_names gives them).\n\n"
          "default: the value of the joints the mapping leaves out: a number, or a (dof,) array read at\n"
          "  their places; None: every joint must be given. Raises ValueError for a name the chain has\n"
          "  not (listing its joints), for joints left out without a default (listing them) and for\n"
          "  values that are not finite; TypeError for a mapping or value of the wrong kind.");
  cls.def("q_dict", &q_dict, py::arg("q"),
          "{joint name: value} of q (dof,), in the chain's joint order (the inverse of q_from).");
}

}  // namespace robokin::bind
