// Options structs and result structs of the core, bound mechanically.
//
// An algorithm's options are one core struct (defaults on its fields, `validate()` with named
// messages). Here each is bound once, field by field (`def_readwrite`), and filled from a call's
// keyword arguments by one generic helper; unknown keywords and values of the wrong kind are a
// TypeError naming the keyword. Results get a generic `__repr__` from their field names.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <string>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;

// The names of T's bound fields, in binding order (for kwargs, __repr__, signatures).
template <class T>
std::vector<std::string>& field_names() {
  static std::vector<std::string> names;
  return names;
}

// `ClassName(a=1, b=array(...))` from the named attributes of obj; arrays of more than 8 numbers
// are summarised by shape and dtype.
inline std::string repr_fields(py::handle obj, const std::vector<std::string>& names) {
  std::string s = py::str(py::type::of(obj).attr("__name__")).cast<std::string>() + "(";
  for (std::size_t i = 0; i < names.size(); ++i) {
    py::object v = obj.attr(names[i].c_str());
    std::string text;
    if (py::isinstance<py::array>(v) && py::reinterpret_borrow<py::array>(v).size() > 8) {
      const py::array a = py::reinterpret_borrow<py::array>(v);
      std::string shape = "(";
      for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
      text = "<array " + shape + (a.ndim() == 1 ? ",)" : ")") + " " + py::str(a.dtype()).cast<std::string>() + ">";
    } else {
      text = py::repr(v).cast<std::string>();
    }
    s += (i ? ", " : "") + names[i] + "=" + text;
  }
  return s + ")";
}

// Binds an options struct: a keyword-only constructor, one read-write property per field, equality,
// a generic __repr__ and `fields` (the names, in order). Fields are declared with `field`.
template <class T>
class OptionsClass {
 public:
  OptionsClass(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc) {
    cls_.def(py::init([](const py::kwargs& kwargs) { return from_kwargs(kwargs); }),
             "Every option as a keyword argument; the ones not given keep their defaults.");
    cls_.def("__repr__", [](py::handle self) { return repr_fields(self, field_names<T>()); });
    cls_.def("__eq__", [](py::handle self, py::handle other) {
      if (!py::isinstance(other, py::type::of(self))) return false;
      for (const std::string& n : field_names<T>())
        if (!self.attr(n.c_str()).equal(other.attr(n.c_str()))) return false;
      return true;
    });
    cls_.def(py::pickle([](py::handle self) {
                          py::dict state;
                          for (const std::string& n : field_names<T>()) state[n.c_str()] = self.attr(n.c_str());
                          return state;
                        },
                        [](const py::dict& state) { return from_kwargs(state); }));
    cls_.def_property_readonly_static("fields", [](py::handle) {
      py::tuple names(field_names<T>().size());
      for (std::size_t i = 0; i < field_names<T>().size(); ++i) names[i] = py::str(field_names<T>()[i]);
      return names;
    }, "The option names, in order.");
  }

  template <class V>
  OptionsClass& field(const char* name, V T::*member, const char* doc) {
    cls_.def_readwrite(name, member, doc);
    field_names<T>().emplace_back(name);
    return *this;
  }

  // T from keyword arguments (a dict): each must name a field and convert to its type.
  static T from_kwargs(const py::handle& kwargs) {
    py::object obj = py::cast(T{});
    for (auto item : py::reinterpret_borrow<py::dict>(kwargs)) {
      const std::string name = py::str(item.first).cast<std::string>();
      const auto& names = field_names<T>();
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw py::type_error("unexpected keyword argument '" + name + "' (options: " + join(names) + ")");
      try {
        obj.attr(name.c_str()) = item.second;
      } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_TypeError)) throw;
        const std::string expected = py::str(obj.attr(name.c_str()).get_type().attr("__name__")).cast<std::string>();
        const std::string got = py::str(item.second.get_type().attr("__name__")).cast<std::string>();
        // An int too large for the field's C type converts to nothing: a bad value, not a bad kind.
        if (got == expected) throw py::value_error(name + ": out of range, got " + py::repr(item.second).cast<std::string>());
        throw py::type_error(name + ": expected " + expected + ", got " + got);
      }
    }
    return obj.cast<T>();
  }

 private:
  py::class_<T> cls_;

  static std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  }
};

}  // namespace robokin::bind
