// Hooks for the test suite only (underscored names): they drive machinery that no public call
// reaches on demand, an exception thrown on a worker thread of parallel_for and the translation of
// the exception types the core and KDL may throw.
#include <kdl/utilities/error.h>

#include <atomic>
#include <chrono>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>

#include "../src/fast_math.hpp"
#include "arrays.hpp"
#include "bindings.hpp"
#include "progress.hpp"
#include "robokin/parallel.hpp"

namespace robokin::bind {

void bind_testing(pybind11::module_& m) {
  m.def(
      "_parallel_for_throwing",
      [](long count, bool on_caller) {
        // Each item takes a millisecond, so that every thread gets some; the items run on the
        // calling thread (or on the other threads) throw. Returns how many items ran.
        const auto caller = std::this_thread::get_id();
        std::atomic<long> ran{0};
        PythonProgress progress("_parallel_for_throwing");
        pybind11::gil_scoped_release release;
        parallel_for(count, 1, [&](long, long) {
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
          ++ran;
          if ((std::this_thread::get_id() == caller) == on_caller) throw std::runtime_error("thrown on purpose");
        }, &progress);
        return ran.load();
      },
      pybind11::arg("count"), pybind11::arg("on_caller"));
  // The batch paths' vectorised sin, cos and atan2 (cpp/src/fast_math.hpp) on float64 arrays.
  m.def("_vmath_sincos", [](const pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>& x) {
    pybind11::array_t<double> s(x.size()), c(x.size());
    vmath::sincos(x.data(), s.mutable_data(), c.mutable_data(), static_cast<long>(x.size()));
    return pybind11::make_tuple(s, c);
  });
  m.def("_vmath_atan2", [](const pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>& y,
                           const pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>& x) {
    if (x.size() != y.size()) fail("x: expected as many values as y");
    pybind11::array_t<double> out(x.size());
    vmath::atan2(y.data(), x.data(), out.mutable_data(), static_cast<long>(x.size()));
    return out;
  });
  m.def("_throw", [](const std::string& kind) {
    if (kind == "kdl") throw KDL::Error_Not_Implemented();
    if (kind == "bad_alloc") throw std::bad_alloc();
    if (kind == "logic") throw std::logic_error("a logic error");
    if (kind == "interrupted") throw Interrupted();
    throw 42;  // not an exception class at all
  });
}

}  // namespace robokin::bind
