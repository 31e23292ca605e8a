// C++ exceptions that pybind11 does not translate by itself. None may reach Python as a crash or
// as pybind11's "Caught an unknown exception!".
#include <kdl/utilities/error.h>

#include "bindings.hpp"
#include "robokin/progress.hpp"

namespace robokin::bind {

void bind_errors(pybind11::module_&) {
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted&) {
      // Stopped by PythonProgress, which left the KeyboardInterrupt (or what a signal handler
      // raised) set: it is what Python sees.
      if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const KDL::Error& e) {  // KDL's own hierarchy, not a std::exception
      PyErr_SetString(PyExc_RuntimeError, (std::string("Orocos KDL: ") + e.Description()).c_str());
    }
  });
}

}  // namespace robokin::bind
