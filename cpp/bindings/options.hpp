// Options structs and result structs of the core, bound mechanically.
//
// An algorithm's options are one core struct (defaults on its fields, `validate()` with named
// messages). Here each is bound once, field by field (`def_readwrite`), and filled from a call's
// keyword arguments by one generic helper; unknown keywords and values of the wrong kind are a
// TypeError naming the keyword. Results get a generic `__repr__` from their field names.
#pragma once

#include "arrays.hpp"
#include "bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace robokin::bind {

namespace py = pybind11;

// What a field takes, for messages: "int", "float", "bool", "str", "None or an int", ...
template <class V>
struct FieldKind {
  static constexpr bool integer = std::is_integral_v<V> && !std::is_same_v<V, bool>;
  static std::string name() {
    if constexpr (std::is_same_v<V, bool>) return "bool";
    else if constexpr (integer) return "int";
    else if constexpr (std::is_floating_point_v<V>) return "float";
    else return "str";
  }
};
template <class V>
struct FieldKind<std::optional<V>> {
  static constexpr bool integer = FieldKind<V>::integer;
  static std::string name() { return "None or " + FieldKind<V>::name(); }
};

// A field of a type Python sees as another (a list of numbers as a tuple; the 3-RRR's working mode
// as a tuple of signs, specialised beside its bindings): kind() says what it takes in words, Arg
// what the stubs show, to_python(v) gives the Python value, from_python(obj, name) converts and
// checks it, a ValueError naming the field when it does not fit.
template <class V>
struct FieldCodec {
  static constexpr bool defined = false;
};
template <>
struct FieldCodec<std::vector<double>> {
  static constexpr bool defined = true;
  using Arg = ArrayLike;  // what the stubs show
  static std::string kind() { return "sequence of float"; }
  static py::tuple to_python(const std::vector<double>& v) { return py::tuple(py::cast(v)); }
  static std::vector<double> from_python(py::handle obj, const char* name) {
    const Eigen::VectorXd a = as_vector(obj, name);
    return {a.data(), a.data() + a.size()};
  }
};

template <class V>
struct OptionalEnum : std::false_type {};
template <class E>
struct OptionalEnum<std::optional<E>> : std::is_enum<E> {};

struct FieldInfo {
  std::string name, kind;
  bool integer;  // an int field: bools are refused, ints too large for it are out of range
};

// T's bound fields, in binding order (for kwargs, __repr__, signatures).
template <class T>
std::vector<FieldInfo>& fields_of() {
  static std::vector<FieldInfo> fields;
  return fields;
}

// T's fields' setters from a Python value, in the order of fields_of<T>() (from_kwargs calls them
// on the struct directly: no Python attribute machinery per keyword).
template <class T>
std::vector<std::function<void(T&, py::handle)>>& setters_of() {
  static std::vector<std::function<void(T&, py::handle)>> setters;
  return setters;
}

template <class T>
std::vector<std::string> field_names() {
  std::vector<std::string> names;
  for (const FieldInfo& f : fields_of<T>()) names.push_back(f.name);
  return names;
}

// A field's default as a docstring shows it: its repr, or "RRR3LoopOptions().nominals" when that
// is long (a table of values).
template <class T>
std::string default_text(const std::string& name) {
  const py::object value = py::cast(T{}).attr(name.c_str());
  const std::string text = py::repr(value).cast<std::string>();
  if (text.size() <= 40) return text;
  return py::str(py::type::of<T>().attr("__name__")).cast<std::string>() + "()." + name;
}

// "Options (keyword-only, RRR3PlanOptions):" and a line per field of T (bound before): its name,
// kind, default and doc (the header's), as robokin._options.options_section writes them in Python.
template <class T>
std::string options_doc() {
  const py::object cls = py::type::of<T>();
  std::string s = "Options (keyword-only, " + py::str(cls.attr("__name__")).cast<std::string>() + "):";
  for (const FieldInfo& f : fields_of<T>()) {
    const py::object doc = cls.attr(f.name.c_str()).attr("__doc__");
    s += "\n    " + f.name + " (" + f.kind + ", default " + default_text<T>(f.name) +
         "): " + (doc.is_none() ? std::string() : doc.cast<std::string>());
  }
  return s;
}

// The docstring of a core call that takes T's fields as **kwargs: "plan(points, *, phi=0.0, ...)"
// from head and the options' defaults, the text, then options_doc<T>().
template <class T>
std::string kwargs_doc(const std::string& head, const std::string& text) {
  std::string s = head;
  for (const std::string& n : field_names<T>()) s += ", " + n + "=" + default_text<T>(n);
  return s + ")\n\n" + text + "\n\n" + options_doc<T>();
}

// A read-only numpy view of a result struct's buffer, kept alive by the result object (no copy).
template <class V>
py::array result_view(py::handle owner, const V* data, std::vector<py::ssize_t> shape) {
  py::array a = py::array_t<V>(shape, data, owner);
  set_read_only(a);
  return a;
}

// A result's Eigen member (vector, array or matrix) as a read-only numpy view: (rows,) for a
// column, (rows, cols) otherwise.
template <class T, class M>
void def_array(py::class_<T>& cls, const char* name, M T::*member, const char* doc) {
  cls.def_property_readonly(name, [member](py::handle self) {
    const M& a = self.cast<const T&>().*member;
    if constexpr (M::ColsAtCompileTime == 1) return result_view(self, a.data(), {a.rows()});
    else return result_view(self, a.data(), {a.rows(), a.cols()});
  }, doc);
}

// Whether T has `void validate() const` (options checked on their own, not against a model).
template <class T, class = void>
struct HasValidate : std::false_type {};
template <class T>
struct HasValidate<T, std::void_t<decltype(std::declval<const T&>().validate())>> : std::true_type {};

// Binds an options struct: a keyword-only constructor, one read-write property per field, equality,
// a generic __repr__ and `fields` (the names, in order). Fields are declared with `field`, or all at
// once from the struct's own list (`fields()`, from `T::fields` in its header).
template <class T>
class OptionsClass {
 public:
  OptionsClass(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc) {
    cls_.def(py::init([](const py::kwargs& kwargs) { return from_kwargs(kwargs); }),
             "Every option as a keyword argument; the ones not given keep their defaults.");
    cls_.def("__repr__", [](py::handle self) { return printed("fields_repr", self, field_names<T>()); });
    if constexpr (HasValidate<T>::value)
      cls_.def("validate", &T::validate, "Raises ValueError naming an option out of range.");
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
    cls_.def_property_readonly_static(
        "fields", [](py::handle) { return py::tuple(py::cast(field_names<T>())); }, "The option names, in order.");
    cls_.def_property_readonly_static("kinds", [](py::handle) {
      std::vector<std::string> kinds;
      for (const FieldInfo& f : fields_of<T>()) kinds.push_back(f.kind);
      return py::tuple(py::cast(kinds));
    }, "What each option takes, in the order of fields: 'int', 'float', 'bool', 'str', 'None or int', ...");
  }

  // One field: read-write as its C++ type, an enum by its name (the core's name_of / parse
  // overloads beside the enum; an optional enum: None or a name), a type with a FieldCodec as its
  // codec says.
  template <class V>
  OptionsClass& field(const char* name, V T::*member, const char* doc) {
    if constexpr (std::is_enum_v<V>) {
      return field_as<std::string>(
          name, [member](const T& o) { return std::string(name_of(o.*member)); },
          [member](T& o, const std::string& v) { parse(v, o.*member); }, doc);
    } else if constexpr (OptionalEnum<V>::value) {
      using Name = std::optional<std::string>;
      return field_as<Name>(
          name, [member](const T& o) { return o.*member ? Name(name_of(*(o.*member))) : Name(); },
          [member](T& o, const Name& v) {
            if (!v) return (o.*member).reset();
            typename V::value_type e{};
            parse(*v, e);
            o.*member = e;
          },
          doc);
    } else if constexpr (FieldCodec<V>::defined) {
      using Codec = FieldCodec<V>;
      cls_.def_property(name, [member](const T& o) { return Codec::to_python(o.*member); },
                        [member, name](T& o, typename Codec::Arg v) { o.*member = Codec::from_python(v, name); }, doc);
      fields_of<T>().push_back({name, Codec::kind(), false});
      setters_of<T>().push_back([member, name](T& o, py::handle v) { o.*member = Codec::from_python(v, name); });
      return *this;
    } else {
      cls_.def_readwrite(name, member, doc);
      fields_of<T>().push_back({name, FieldKind<V>::name(), FieldKind<V>::integer});
      setters_of<T>().push_back([member](T& o, py::handle v) { o.*member = v.cast<V>(); });
      return *this;
    }
  }

  // Every field the struct lists in its header (`T::fields`: keyword, member, doc), in that order.
  OptionsClass& fields() {
    T::fields([this](const char* name, auto member, const char* doc) { field(name, of_t(member), doc); });
    return *this;
  }

  // A field shown to Python as another type V (an enum as its name): get(const T&) -> V, set(T&, V).
  template <class V, class Get, class Set>
  OptionsClass& field_as(const char* name, Get get, Set set, const char* doc) {
    cls_.def_property(name, get, set, doc);
    fields_of<T>().push_back({name, FieldKind<V>::name(), false});
    setters_of<T>().push_back([set](T& o, py::handle v) { set(o, v.cast<V>()); });
    return *this;
  }

  // T from keyword arguments (a dict): each must name a field and convert to its type.
  static T from_kwargs(const py::handle& kwargs) {
    T o{};
    const auto& fields = fields_of<T>();
    for (auto item : py::reinterpret_borrow<py::dict>(kwargs)) {
      const std::string name = py::str(item.first).cast<std::string>();
      const auto f = std::find_if(fields.begin(), fields.end(), [&](const FieldInfo& x) { return x.name == name; });
      if (f == fields.end())
        throw py::type_error("unexpected keyword argument '" + name + "' (options: " + join(field_names<T>()) + ")");
      if (f->integer && PyBool_Check(item.second.ptr())) throw py::type_error(name + ": expected " + f->kind + ", got bool");
      try {
        setters_of<T>()[static_cast<std::size_t>(f - fields.begin())](o, item.second);
      } catch (const py::cast_error&) {
        bad_value(*f, item.second);
      } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_TypeError)) throw;
        bad_value(*f, item.second);
      }
    }
    return o;
  }

 private:
  py::class_<T> cls_;

  // A field of a base of T (options extending another's, as ServoOptions does RateOptions) as T's.
  template <class V, class B>
  static V T::*of_t(V B::*member) {
    static_assert(std::is_base_of_v<B, T>, "a field of T or of a base of T");
    return member;
  }

  // A value that did not convert: an int too large for the field's C type is a bad value (out of
  // range), anything else a bad kind.
  [[noreturn]] static void bad_value(const FieldInfo& f, py::handle value) {
    if (f.integer && PyIndex_Check(value.ptr()))
      throw py::value_error(f.name + ": out of range, got " + py::repr(value).cast<std::string>());
    const std::string got = py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
    throw py::type_error(f.name + ": expected " + f.kind + ", got " + got);
  }

  static std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  }
};

// A call's options from its keyword arguments (a dict), validated on their own when T has
// validate(); options checked against a model (ReachOptions' validate(chain)) are the caller's to check.
template <class T>
T options_arg(const py::handle& kwargs) {
  T o = OptionsClass<T>::from_kwargs(kwargs);
  if constexpr (HasValidate<T>::value) o.validate();
  return o;
}

}  // namespace robokin::bind
