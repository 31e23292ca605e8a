// The hottest single calls (Chain.fk, Chain.jacobian, ik) bound without pybind11's dispatcher:
// CPython's METH_FASTCALL | METH_KEYWORDS convention, the arguments read where CPython passes them.
// The dispatcher's own work (an argument vector and a function record per call, type lookups, a
// bound method object per call) was a large part of a microsecond call. What stays as before:
// the same argument names, defaults and conversions (the functions' bodies are unchanged), C++
// exceptions translated by pybind11's registered translators as the dispatcher does, and a
// docstring whose first line is the signature pybind11 writes (help(), the generated stubs).
#pragma once

#include <pybind11/pybind11.h>

#include <cxxabi.h>

#include <cstring>
#include <string>

namespace robokin::bind {

namespace py = pybind11;

// The arguments of one call by name. `names` are the parameters in order, the first `positional`
// of them positional-or-keyword, the rest keyword-only; slot i of `out` receives parameter i
// (borrowed) or stays null when not given. A keyword that names no parameter goes to
// `extra(name, value)` (a function taking **kwargs), or is a TypeError when `extra` is null.
// Missing required parameters are the caller's to report (missing()).
template <class Extra>
void parse_args(const char* fname, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames, const char* const* names,
                int count, int positional, PyObject** out, Extra* extra) {
  if (nargs > positional)
    throw py::type_error(std::string(fname) + "() takes at most " + std::to_string(positional) +
                         " positional arguments (" + std::to_string(nargs) + " given)");
  for (int i = 0; i < count; ++i) out[i] = i < nargs ? args[i] : nullptr;
  if (!kwnames) return;
  const Py_ssize_t nkw = PyTuple_GET_SIZE(kwnames);
  for (Py_ssize_t k = 0; k < nkw; ++k) {
    PyObject* key = PyTuple_GET_ITEM(kwnames, k);
    PyObject* value = args[nargs + k];
    const char* name = PyUnicode_AsUTF8(key);
    if (!name) throw py::error_already_set();
    int i = 0;
    while (i < count && std::strcmp(name, names[i]) != 0) ++i;
    if (i == count) {
      if (!extra) throw py::type_error(std::string(fname) + "() got an unexpected keyword argument '" + name + "'");
      (*extra)(key, value);
      continue;
    }
    if (out[i]) throw py::type_error(std::string(fname) + "() got multiple values for argument '" + name + "'");
    out[i] = value;
  }
}

// parse_args for a function without **kwargs.
inline void parse_args(const char* fname, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames,
                       const char* const* names, int count, int positional, PyObject** out) {
  struct None {
    void operator()(PyObject*, PyObject*) const {}
  };
  parse_args<None>(fname, args, nargs, kwnames, names, count, positional, out, nullptr);
}

// A str made once and kept (a parameter's default).
inline PyObject* interned(const char* text) {
  PyObject* s = PyUnicode_InternFromString(text);
  if (!s) throw py::error_already_set();
  return s;
}

[[noreturn]] inline void missing(const char* fname, const char* name) {
  throw py::type_error(std::string(fname) + "() missing required argument '" + name + "'");
}

// Runs body() (a py::object) for CPython: the new reference, or null with the Python error set.
template <class Body>
PyObject* guarded(Body&& body) noexcept {
  try {
    return body().release().ptr();
  } catch (py::error_already_set& e) {
    e.restore();
  } catch (abi::__forced_unwind&) {  // thread cancellation must unwind on (as in pybind11)
    throw;
  } catch (...) {
    py::detail::try_translate_exceptions();
  }
  return nullptr;
}

// The C++ object of a bound instance (the method descriptor has checked its type already). An
// instance of exactly T is read directly: its one value, without pybind11's lookups of the type
// (two hash-table searches a call); a subclass's, or one never initialised (an error), through
// pybind11's cast.
template <class T>
T& self_of(PyObject* self) {
  static PyTypeObject* const exact = reinterpret_cast<PyTypeObject*>(py::type::of<T>().ptr());
  if (Py_TYPE(self) == exact)
    if (T* value = reinterpret_cast<py::detail::instance*>(self)->get_value_and_holder().value_ptr<T>())
      return *value;
  return py::handle(self).cast<T&>();
}

// A positional-or-keyword argument that must be an instance of the bound class T: TypeError
// naming it otherwise (pybind11 said "incompatible function arguments").
template <class T>
const T& instance_arg(const char* fname, const char* name, PyObject* obj) {
  if (!obj) missing(fname, name);
  if (!py::isinstance<T>(obj))
    throw py::type_error(std::string(fname) + "(): " + name + ": expected " +
                         py::str(py::type::of<T>().attr("__name__")).cast<std::string>() + ", got " +
                         py::str(py::type::handle_of(obj).attr("__name__")).cast<std::string>());
  return py::handle(obj).cast<const T&>();
}

using FastFunction = PyObject* (*)(PyObject* self, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames);

// A parameter type's text as pybind11 writes it in signatures (ArrayLike, the Typed<Tag> handles of
// arrays.hpp): the fast methods' signature lines take the same words the stub has elsewhere.
template <class T>
std::string type_text() {
  return py::detail::handle_type_name<T>::name.text;
}

// The method table entry of `fn`, kept for the process (as the function it describes). Its docstring
// is name + `signature` (the parameters and return annotation as pybind11 writes them: help() and
// the stub generator read that first line), a blank line, then `doc`.
inline PyMethodDef* fast_def(const char* name, FastFunction fn, const std::string& signature, const char* doc) {
  const std::string* text = new std::string(name + signature + "\n\n" + doc);
  return new PyMethodDef{name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(fn)),
                         METH_FASTCALL | METH_KEYWORDS, text->c_str()};
}

// Installs `def` (kept for the process) as a method of the bound class `cls`, replacing what is there.
inline void add_fast_method(py::handle cls, PyMethodDef* def) {
  PyObject* descr = PyDescr_NewMethod(reinterpret_cast<PyTypeObject*>(cls.ptr()), def);
  if (!descr) throw py::error_already_set();
  const int status = PyObject_SetAttrString(cls.ptr(), def->ml_name, descr);
  Py_DECREF(descr);
  if (status != 0) throw py::error_already_set();
}

// Installs `def` (kept for the process) as the function m.<name>.
inline void add_fast_function(py::module_& m, PyMethodDef* def) {
  py::object f = py::reinterpret_steal<py::object>(PyCFunction_NewEx(def, nullptr, m.attr("__name__").ptr()));
  if (!f) throw py::error_already_set();
  m.attr(def->ml_name) = f;
}

}  // namespace robokin::bind
