// Result structs of the core, bound mechanically: each field once, from the struct's own list
// (`T::fields` in its header: name, member, doc) or one by one (a scalar, string or bound class
// read-only, an Eigen member as a read-only numpy array, or as Python computes it from the struct),
// and from that list a generic __repr__, a versioned pickle (kStateVersion, field values in order),
// a __str__ for people and, for a batch result, __len__.
#pragma once

#include "arrays.hpp"
#include "options.hpp"

#include <pybind11/pybind11.h>

#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;

// A result's attribute made at its first read and kept in the instance's __dict__ (the class is bound
// with py::dynamic_attr): make() -> a pybind11 object type R; an array is made read-only, so that the
// kept value cannot be changed behind the result. Results never change, so the kept value stays true.
template <class Make>
auto kept_attribute(py::handle self, const char* name, Make make) -> decltype(make()) {
  using R = decltype(make());
  const auto dict = py::reinterpret_steal<py::object>(PyObject_GenericGetDict(self.ptr(), nullptr));
  if (!dict) throw py::error_already_set();
  if (PyObject* kept = PyDict_GetItemString(dict.ptr(), name)) return py::reinterpret_borrow<R>(kept);
  R value = make();
  if (py::isinstance<py::array>(value)) set_read_only(py::reinterpret_borrow<py::array>(value));
  if (PyDict_SetItemString(dict.ptr(), name, value.ptr()) != 0) throw py::error_already_set();
  return value;
}

// A read-only property of T's class made by get(const T&) at its first read and kept (kept_attribute).
template <class T, class Get>
void def_kept(py::class_<T>& cls, const char* name, Get get, const char* doc) {
  cls.def_property_readonly(name, [name, get](py::handle self) {
    return kept_attribute(self, name, [&] { return get(self.cast<const T&>()); });
  }, doc);
}

template <class T>
class ResultClass {
 public:
  // batch: every array field has one row per item (checked on unpickling; __len__ is the rows).
  ResultClass(py::module_& m, const char* name, const char* doc, bool batch)
      : cls_(m, name, doc, py::dynamic_attr()), name_(name), batch_(batch) {}

  // A field bound as it is, read-only: a scalar, a string, or a class bound before (a result inside
  // a result).
  template <class V>
  ResultClass& value(const char* name, V T::*member, const char* doc) {
    cls_.def_readonly(name, member, doc);
    names_.push_back(name);
    restore_.push_back([member](T& r, py::handle v, const char*, long) { r.*member = v.cast<V>(); });
    return *this;
  }

  // A field shown as Python computes it from the struct: get(const T&) -> Python value (kept by
  // kept_attribute when it is a Python object), and its inverse for unpickling, set(T&, py::handle)
  // (which checks what it reads; the fields before it are already restored).
  template <class Get, class Set>
  ResultClass& value_as(const char* name, Get get, Set set, const char* doc) {
    using R = decltype(get(std::declval<const T&>()));
    if constexpr (std::is_base_of_v<py::object, R>) {  // a Python object (an array): made once, kept
      def_kept(cls_, name, get, doc);
    } else {
      cls_.def_property_readonly(name, get, doc);
    }
    names_.push_back(name);
    restore_.push_back([set](T& r, py::handle v, const char*, long) { set(r, v); });
    return *this;
  }

  // An Eigen member (vector or array: (rows,), row-major matrix: (rows, cols)), read-only: in a batch
  // result a view of the result's buffer (def_array); otherwise a copy kept by kept_attribute (a
  // copy, not a view: a view kept by its own base would be a reference cycle, holding a large
  // result until the garbage collector runs).
  template <class M>
  ResultClass& array(const char* name, M T::*member, const char* doc) {
    using Scalar = typename M::Scalar;
    static_assert(M::ColsAtCompileTime == 1 || M::IsRowMajor, "array(): a column or a row-major matrix");
    if (batch_) {
      def_array(cls_, name, member, doc);
    } else {
      cls_.def_property_readonly(name, [member, key = std::string(name)](py::handle self) {
        return kept_attribute(self, key.c_str(), [&]() -> py::array_t<Scalar> {
          const M& a = self.cast<const T&>().*member;
          if constexpr (M::ColsAtCompileTime == 1) return array_of(a.data(), {a.rows()});
          else return array_of(a.data(), {a.rows(), a.cols()});
        });
      }, doc);
    }
    names_.push_back(name);
    restore_.push_back([member](T& r, py::handle v, const char* field, long rows) {
      const auto a = aligned_array<Scalar>(v);
      constexpr int ndim = M::ColsAtCompileTime == 1 ? 1 : 2;
      constexpr int fixed_rows = M::RowsAtCompileTime, fixed_cols = M::ColsAtCompileTime;
      if (!a || a.ndim() != ndim || (rows >= 0 && a.shape(0) != rows) ||
          (fixed_rows != Eigen::Dynamic && a.shape(0) != fixed_rows) ||
          (ndim == 2 && fixed_cols != Eigen::Dynamic && a.shape(1) != fixed_cols))
        fail(std::string("state: ") + field + " is not an array of the result's shape");
      const Eigen::Index n = a.shape(0), cols = ndim == 2 ? a.shape(1) : 1;
      r.*member = Eigen::Map<const M>(a.data(), n, cols);
    });
    return *this;
  }

  // Every field the struct lists in its header (`T::fields`: name, member, doc), in that order: an
  // Eigen member as array(), any other as value().
  ResultClass& fields() {
    T::fields([this](const char* name, auto member, const char* doc) {
      using V = std::decay_t<decltype(std::declval<const T&>().*member)>;
      if constexpr (std::is_base_of_v<Eigen::EigenBase<V>, V>) array(name, member, doc);
      else value(name, member, doc);
    });
    return *this;
  }

  // After the fields: __repr__, pickle, and __len__ of a batch.
  void done() {
    const std::vector<std::string> names = names_;
    cls_.def("__repr__", [names](py::handle self) { return printed("fields_repr", self, names); });
    // print(result): a field per line, long arrays by shape and range.
    cls_.def("__str__", [names](py::handle self) { return printed("summary", self, names); });
    cls_.def(py::pickle(
        [names](py::handle self) {
          py::tuple state(names.size() + 1);
          state[0] = py::int_(kStateVersion);
          for (std::size_t i = 0; i < names.size(); ++i) state[i + 1] = self.attr(names[i].c_str());
          return state;
        },
        [names, restore = restore_, batch = batch_, what = name_](const py::tuple& t) {
          check_state(t, names.size() + 1, what.c_str());
          T r;
          long rows = -1;  // a batch: the rows of its first array field, which the others must match
          for (std::size_t i = 0; i < names.size(); ++i) {
            restore[i](r, t[i + 1], names[i].c_str(), batch ? rows : -1);
            if (batch && rows < 0 && py::isinstance<py::array>(t[i + 1]))
              rows = static_cast<long>(py::reinterpret_borrow<py::array>(t[i + 1]).shape(0));
          }
          return r;
        }));
    if (batch_) {
      const std::string first = names_.front();
      cls_.def("__len__", [first](py::handle self) { return py::len(self.attr(first.c_str())); });
    }
  }

  // done(), then `extra(cls)` for what the type adds (e.g. __bool__).
  template <class Extra>
  void done_with(Extra extra) {
    done();
    extra(cls_);
  }

 private:
  py::class_<T> cls_;
  std::string name_;
  bool batch_;
  std::vector<std::string> names_;
  std::vector<std::function<void(T&, py::handle, const char*, long)>> restore_;
};

}  // namespace robokin::bind
