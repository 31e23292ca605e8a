// The one table of C++ exceptions that pybind11 does not translate by itself (std::invalid_argument
// and the other std::exception types it does). None may reach Python as a crash or as pybind11's
// "Caught an unknown exception!".
#include <kdl/utilities/error.h>

#include "bindings.hpp"
#include "robokin/progress.hpp"
#include "robokin/rrr3.hpp"
#include "robokin/rrr3_connect.hpp"

namespace robokin::bind {
namespace {

// A robokin.errors exception (looked up when raised: the import order of the package does not
// matter) with the message what and one attribute.
template <class Value>
void raise_error(const char* class_name, const char* what, const char* attribute, const Value& value) {
  pybind11::object cls = pybind11::module_::import("robokin.errors").attr(class_name);
  pybind11::object exc = cls(what);
  exc.attr(attribute) = value;
  PyErr_SetObject(cls.ptr(), exc.ptr());
}

}  // namespace

void bind_errors(pybind11::module_&) {
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted&) {
      // Stopped by PythonProgress, which left the KeyboardInterrupt (or what a signal handler
      // raised) set: it is what Python sees.
      if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const LegUnreachable& e) {  // robokin.UnreachableError, a ValueError naming the leg
      raise_error("UnreachableError", e.what(), "leg", e.leg());
    } catch (const NoRoute& e) {  // robokin.NoRouteError, a ValueError with the reason
      raise_error("NoRouteError", e.what(), "reason", e.reason());
    } catch (const KDL::Error& e) {  // KDL's own hierarchy, not a std::exception
      PyErr_SetString(PyExc_RuntimeError, (std::string("Orocos KDL: ") + e.Description()).c_str());
    }
  });
}

}  // namespace robokin::bind
