// The table of fast methods (internals.hpp): the Chain methods whose every call is cheap, so that
// pybind11's dispatcher would be a large part of it. A method is kept here only while its gain
// over a pybind11 .def of the same function is 10 % or more (benchmarks/README.md says how it was
// measured); everything else is bound with .def.
#include "arrays.hpp"
#include "chain_parts.hpp"

#include "robokin/task.hpp"

namespace robokin::bind {

PyObject* fallback_object(const std::string& source) {
  if (source == "None") return Py_None;  // immortal for this process's purposes: kept by the module
  if (source.size() < 2 || source.front() != '\'' || source.back() != '\'')
    throw std::logic_error("fast method default: expected None or a quoted string, got " + source);
  PyObject* s = PyUnicode_InternFromString(source.substr(1, source.size() - 2).c_str());
  if (!s) throw py::error_already_set();
  return s;  // kept for the process
}

void install_fast_method(py::handle cls, const char* name, PyCFunction call, const std::vector<FastParam>& params,
                         const std::vector<std::string>& types, int positional, const char* returns, const char* doc) {
  std::string signature = std::string(name) + "(self: " + py::str(cls.attr("__module__")).cast<std::string>() + "." +
                          py::str(cls.attr("__name__")).cast<std::string>();
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (static_cast<int>(i) == positional) signature += ", *";
    signature += std::string(", ") + params[i].name + ": " + types[i];
    if (!params[i].fallback.empty()) signature += " = " + params[i].fallback;
  }
  // The method table entry and its docstring, kept for the process (as the method they describe).
  const std::string* text = new std::string(signature + ") -> " + returns + "\n\n" + doc);
  auto* def = new PyMethodDef{name, call, METH_FASTCALL | METH_KEYWORDS, text->c_str()};
  PyObject* descr = PyDescr_NewMethod(reinterpret_cast<PyTypeObject*>(cls.ptr()), def);
  if (!descr) throw py::error_already_set();
  const int status = PyObject_SetAttrString(cls.ptr(), name, descr);
  Py_DECREF(descr);
  if (status != 0) throw py::error_already_set();
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
      cls, "manipulability", {{"q", ""}, {"measure", "'yoshikawa'"}, {"task", "None"}}, 3,
      "float | numpy.typing.NDArray[numpy.float64]",
      "Manipulability at q by measure, from the singular values of the task's Jacobian rows:\n"
      "'yoshikawa' their product (sqrt(det(J J^T)) when rows <= dof), 'condition' sigma_min /\n"
      "sigma_max (the inverse condition number, 1 isotropic, 0 singular), 'min_singular' sigma_min.\n"
      "A float for q (dof,), an array (N,) for a batch (N, dof) (GIL released, every core). task\n"
      "None: the chain's natural_task (a planar arm's 'pose' rows would always give 0).\n");
}

}  // namespace robokin::bind
