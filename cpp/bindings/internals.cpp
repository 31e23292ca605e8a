// What internals.hpp declares and does not define inline: a fast method's default values and its
// installation in a bound class (its table: chain.cpp).
#include "internals.hpp"

#include <stdexcept>

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

}  // namespace robokin::bind
