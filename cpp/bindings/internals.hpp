// Everything the bindings take from pybind11's private API (pybind11::detail) and numpy's C API,
// in this file (internals.cpp defines what is not inline); the other binding files use only public
// pybind11. Three things live here:
// - the parameter types that signatures and stubs show by name (ArrayLike, Typed<Tag>);
// - numpy's arrays read and made without pybind11's wrappers (float64_view, new_array, has_flags);
// - fast methods: the hottest Chain methods called without pybind11's dispatcher (fast_method),
//   declared in one table (chain.cpp); internals.cpp installs them.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cxxabi.h>

#include <array>
#include <cstring>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;

// ---- Parameter types shown by name -------------------------------------------------------------

// A parameter that takes anything numpy can convert (arrays, lists, numbers): any object is
// accepted here and converted, with errors naming the argument, by arrays.hpp's helpers. The type
// stubs show it as numpy.typing.ArrayLike.
class ArrayLike : public py::object {
 public:
  using py::object::object;
  static bool check_(py::handle) { return true; }
};

// A parameter of several accepted forms, taken as any object and converted by the bindings'
// helpers (errors naming it), shown in the stubs as the string Text says (a constant of its own).
template <const auto& Text>
class Typed : public py::object {
 public:
  using py::object::object;
  static bool check_(py::handle) { return true; }
};

}  // namespace robokin::bind

namespace pybind11::detail {
template <>
struct handle_type_name<robokin::bind::ArrayLike> {
  static constexpr auto name = const_name("numpy.typing.ArrayLike");
};
template <const auto& Text>
struct handle_type_name<robokin::bind::Typed<Text>> {
  static constexpr auto name = const_name(Text);
};
}  // namespace pybind11::detail

namespace robokin::bind {

// A parameter type's text as pybind11 writes it in signatures (fast methods' signature lines take
// the same words the stub has elsewhere).
template <class T>
std::string type_text() {
  return py::detail::handle_type_name<T>::name.text;
}

// ---- numpy's arrays -----------------------------------------------------------------------------

// numpy's array flags (its C API's values).
constexpr int kCContiguous = py::detail::npy_api::NPY_ARRAY_C_CONTIGUOUS_;
constexpr int kAligned = py::detail::npy_api::NPY_ARRAY_ALIGNED_;
constexpr int kWriteable = py::detail::npy_api::NPY_ARRAY_WRITEABLE_;

inline bool has_flags(const py::array& a, int flags) {
  return (py::detail::array_proxy(a.ptr())->flags & flags) == flags;
}

// Makes a (its data) read-only, as numpy's setflags(write=False) without a Python call.
inline void set_read_only(const py::array& a) { py::detail::array_proxy(a.ptr())->flags &= ~kWriteable; }

// The fast path: obj is exactly a numpy.ndarray of native-order float64, C-contiguous and aligned,
// so its buffer is used as it is (no conversion object, no dtype object, no reference counting).
// Anything else (lists, other dtypes, strided views, subclasses) goes through as_array.
struct Float64View {
  const double* data = nullptr;
  int ndim = 0;
  const py::ssize_t* shape = nullptr;
  py::ssize_t size = 0;
};

inline bool float64_view(py::handle obj, Float64View& view) {
  using py::detail::npy_api;
  const npy_api& api = npy_api::get();
  if (Py_TYPE(obj.ptr()) != api.PyArray_Type_) return false;
  const auto* a = py::detail::array_proxy(obj.ptr());
  const auto* d = py::detail::array_descriptor_proxy(a->descr);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  constexpr char kSwapped = '<';
#else
  constexpr char kSwapped = '>';
#endif
  constexpr int kNeed = kCContiguous | kAligned;
  if (d->type_num != npy_api::NPY_DOUBLE_ || d->byteorder == kSwapped || (a->flags & kNeed) != kNeed) return false;
  view.data = reinterpret_cast<const double*>(a->data);
  view.ndim = a->nd;
  view.shape = a->dimensions;
  view.size = 1;
  for (int i = 0; i < a->nd; ++i) view.size *= a->dimensions[i];
  return true;
}

// A new, uninitialised C-contiguous array of T (float64 unless said): every output the bindings fill
// comes from here. Made by numpy's C API directly (pybind11's array_t constructor builds shape and
// stride vectors and a dtype object first).
template <class T = double>
py::array_t<T> new_array(int ndim, const py::ssize_t* shape) {
  using py::detail::npy_api;
  const npy_api& api = npy_api::get();
  // The reference is stolen below.
  PyObject* descr = api.PyArray_DescrFromType_(py::detail::npy_format_descriptor<T>::value);
  PyObject* a = api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, ndim, shape, nullptr, nullptr, 0, nullptr);
  if (!a) throw py::error_already_set();
  return py::reinterpret_steal<py::array_t<T>>(a);
}
template <class T = double>
py::array_t<T> new_array(std::initializer_list<py::ssize_t> shape) {
  return new_array<T>(static_cast<int>(shape.size()), shape.begin());
}

inline double* float64_data(const py::array& a) {
  return reinterpret_cast<double*>(py::detail::array_proxy(a.ptr())->data);
}

// ---- Fast methods -------------------------------------------------------------------------------
// CPython's METH_FASTCALL | METH_KEYWORDS convention, the arguments read where CPython passes them:
// pybind11's dispatcher (an argument vector and a function record per call, type lookups, a bound
// method object per call) is a large share of a sub-microsecond call (benchmarks/README.md, "Fast
// methods against pybind11's dispatcher"). What stays as with .def: the
// argument names, defaults and conversions (the bound functions are the same), C++ exceptions
// translated by pybind11's registered translators, and a docstring whose first line is the
// signature pybind11 writes (help(), the generated stubs).

// One parameter of a fast method: its name and its default as Python source (None, or a quoted
// string), or an empty default for a required parameter.
struct FastParam {
  const char* name;
  std::string fallback;
};

// The arguments of one call by name: slot i of `out` receives parameter i (borrowed) or stays null.
// The first `positional` parameters may be given by position, the rest by keyword only.
inline void parse_args(const char* fname, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames,
                       const char* const* names, int count, int positional, PyObject** out) {
  if (nargs > positional)
    throw py::type_error(std::string(fname) + "() takes at most " + std::to_string(positional) +
                         " positional arguments (" + std::to_string(nargs) + " given)");
  for (int i = 0; i < count; ++i) out[i] = i < nargs ? args[i] : nullptr;
  if (!kwnames) return;
  const Py_ssize_t nkw = PyTuple_GET_SIZE(kwnames);
  for (Py_ssize_t k = 0; k < nkw; ++k) {
    const char* name = PyUnicode_AsUTF8(PyTuple_GET_ITEM(kwnames, k));
    if (!name) throw py::error_already_set();
    int i = 0;
    while (i < count && std::strcmp(name, names[i]) != 0) ++i;
    if (i == count) throw py::type_error(std::string(fname) + "() got an unexpected keyword argument '" + name + "'");
    if (out[i]) throw py::type_error(std::string(fname) + "() got multiple values for argument '" + name + "'");
    out[i] = args[nargs + k];
  }
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
const T& self_of(PyObject* self) {
  static PyTypeObject* const exact = reinterpret_cast<PyTypeObject*>(py::type::of<T>().ptr());
  if (Py_TYPE(self) == exact)
    if (T* value = reinterpret_cast<py::detail::instance*>(self)->get_value_and_holder().value_ptr<T>())
      return *value;
  return py::handle(self).cast<const T&>();
}

// The fast method calling F(self, args...): every argument after self is a py::object type (an
// ArrayLike, a Typed<Tag>) that F converts and checks itself, and so is its result. One instance per F, set up by
// fast_method below; its names and defaults are kept for the process.
template <auto F>
struct FastMethod;
template <class R, class Self, class... A, R (*F)(const Self&, A...)>
struct FastMethod<F> {
  static_assert(std::is_base_of_v<py::object, R>, "a fast method returns a Python object");
  static constexpr int kCount = sizeof...(A);
  static inline const char* name = nullptr;
  static inline int positional = kCount;
  static inline std::array<const char*, kCount> names{};
  static inline std::array<PyObject*, kCount> fallbacks{};  // null: required

  static PyObject* call(PyObject* self, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames) {
    return guarded([&]() -> py::object {
      PyObject* a[kCount];
      parse_args(name, args, nargs, kwnames, names.data(), kCount, positional, a);
      for (int i = 0; i < kCount; ++i) {
        if (a[i]) continue;
        if (!fallbacks[i]) throw py::type_error(std::string(name) + "() missing required argument '" + names[i] + "'");
        a[i] = fallbacks[i];
      }
      return invoke(self, a, std::index_sequence_for<A...>{});
    });
  }

  template <std::size_t... I>
  static py::object invoke(PyObject* self, PyObject* const* a, std::index_sequence<I...>) {
    return F(self_of<Self>(self), py::reinterpret_borrow<std::decay_t<A>>(a[I])...);
  }

  static std::vector<std::string> types() { return {type_text<std::decay_t<A>>()...}; }
};

// A default's object from its Python source: None, or a quoted string (interned, kept).
PyObject* fallback_object(const std::string& source);

// Installs F as the method `name` of the bound class `cls` (replacing what is there), called
// without pybind11's dispatcher. `params` are F's parameters after self, the first `positional` of
// them positional-or-keyword; the docstring is the signature (with `returns`) and `doc`.
void install_fast_method(py::handle cls, const char* name, PyCFunction call, const std::vector<FastParam>& params,
                         const std::vector<std::string>& types, int positional, const char* returns, const char* doc);

template <auto F>
void fast_method(py::handle cls, const char* name, const std::vector<FastParam>& params, int positional,
                 const char* returns, const char* doc) {
  using M = FastMethod<F>;
  if (params.size() != static_cast<std::size_t>(M::kCount)) throw std::logic_error("fast_method: parameter count");
  M::name = name;
  M::positional = positional;
  for (int i = 0; i < M::kCount; ++i) {
    M::names[i] = params[i].name;
    M::fallbacks[i] = params[i].fallback.empty() ? nullptr : fallback_object(params[i].fallback);
  }
  install_fast_method(cls, name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&M::call)), params,
                      M::types(), positional, returns, doc);
}

}  // namespace robokin::bind
