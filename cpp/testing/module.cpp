// robokin._testing: what the test suite and the benchmarks need and users do not, kept out of the
// public module robokin._core. Hooks that drive machinery no public call reaches on demand (an
// exception thrown on a worker thread of parallel_for, the translation of the exception types the
// core and KDL may throw, Halley's Hessian term) and KDL's position IK as the benchmarks' reference.
// It shares robokin._core's types (Chain) and exception translators: import robokin first.
#include <kdl/utilities/error.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>

#include "../src/ik_starts.hpp"
#include "../src/kernel/fast_math.hpp"
#include "arrays.hpp"
#include "kdl_ik_reference.hpp"
#include "progress.hpp"
#include "robokin/angles.hpp"
#include "robokin/ik.hpp"
#include "robokin/parallel.hpp"
#include "subproblems_hooks.hpp"
#include "targets.hpp"

namespace robokin::bind {
namespace {

void bind_hooks(pybind11::module_& m) {
  m.def(
      "parallel_for_throwing",
      [](long count, bool on_caller) {
        // Each item takes a millisecond, so that every thread gets some; the items run on the
        // calling thread (or on the other threads) throw. Returns how many items ran.
        const auto caller = std::this_thread::get_id();
        std::atomic<long> ran{0};
        PythonProgress progress("parallel_for_throwing");
        pybind11::gil_scoped_release release;
        parallel_for(count, 1, [&](long, long) {
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
          ++ran;
          if ((std::this_thread::get_id() == caller) == on_caller) throw std::runtime_error("thrown on purpose");
        }, &progress);
        return ran.load();
      },
      pybind11::arg("count"), pybind11::arg("on_caller"));
  // The batch paths' vectorised sin, cos and atan2 (cpp/src/kernel/fast_math.hpp) on float64 arrays.
  using Doubles = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;
  m.def("vmath_sincos", [](const Doubles& x) {
    pybind11::array_t<double> s(x.size()), c(x.size());
    vmath::sincos(x.data(), s.mutable_data(), c.mutable_data(), static_cast<long>(x.size()));
    return pybind11::make_tuple(s, c);
  }, pybind11::arg("x"));
  m.def("vmath_atan2", [](const Doubles& y, const Doubles& x) {
    if (x.size() != y.size()) fail("x: expected as many values as y");
    pybind11::array_t<double> out(x.size());
    vmath::atan2(y.data(), x.data(), out.mutable_data(), static_cast<long>(x.size()));
    return out;
  }, pybind11::arg("y"), pybind11::arg("x"));
  // angles.hpp's wrap_angle on a float64 array (tests: the same bits as std::remainder by 2 pi).
  m.def("wrap_angle", [](const Doubles& a) {
    pybind11::array_t<double> out(a.size());
    for (pybind11::ssize_t i = 0; i < a.size(); ++i) out.mutable_data()[i] = wrap_angle(a.data()[i]);
    return out;
  }, pybind11::arg("a"));
  m.def("throw", [](const std::string& kind) {
    if (kind == "kdl") throw KDL::Error_Not_Implemented();
    if (kind == "bad_alloc") throw std::bad_alloc();
    if (kind == "logic") throw std::logic_error("a logic error");
    if (kind == "interrupted") throw Interrupted();
    throw 42;  // not an exception class at all
  });
}

// Frames as a new (count, 4, 4) array.
py::array_t<double> frames_of(const Rigid* F, int count) {
  py::array_t<double> out({static_cast<py::ssize_t>(count), py::ssize_t{4}, py::ssize_t{4}});
  for (int k = 0; k < count; ++k)
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(out.mutable_data() + 16 * k) = F[k].matrix();
  return out;
}

void bind_references(py::module_& m) {
  m.def(
      "hessian_times",
      [](const Chain& chain, py::handle q_obj, py::handle a_obj) {
        const Vector q = as_vector(q_obj, "q", chain.dof()), a = as_vector(a_obj, "a", chain.dof());
        Matrix6X J6(6, chain.dof()), out;
        Rigid T;
        chain.fk_jacobian(q.data(), T, J6.data());
        hessian_times(chain, J6, a, out);
        return to_numpy(out);
      },
      py::arg("chain"), py::arg("q"), py::arg("a"), "sum_j a_j dJ/dq_j (6, dof): Halley's kinematic Hessian term.");
  // Seconds per IkSolver::solve with the default options, timed in C++ over `count` solves of one
  // target from q0: the solver's own work, for the benchmark of what a call from Python adds.
  m.def(
      "ik_solve_seconds",
      [](const Chain& chain, py::handle target, py::handle q0_obj, long count) {
        const IkOptions o;
        const Target t = one_target(chain, o.task_for(chain), target);
        const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
        if (count < 1) fail("count: must be at least 1");
        IkSolver solver(chain, o);
        const auto start = std::chrono::steady_clock::now();
        for (long k = 0; k < count; ++k) solver.solve(t, q0.data(), static_cast<std::uint64_t>(k));
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / count;
      },
      py::arg("chain"), py::arg("target"), py::arg("q0"), py::arg("count"));
  // The chain's stored IK restart configurations (cpp/src/ik_starts.hpp), (kCount, dof).
  m.def(
      "ik_starts",
      [](const Chain& chain) {
        const IkStarts& starts = chain.ik_starts();
        py::array_t<double> out({static_cast<py::ssize_t>(IkStarts::kCount), static_cast<py::ssize_t>(chain.dof())});
        std::copy(starts.q(chain, 0), starts.q(chain, 0) + IkStarts::kCount * chain.dof(), out.mutable_data());
        return out;
      },
      py::arg("chain"));
  // Chain::fk_few (the closed forms' check: up to 8 configurations in one pass of the lane kernel,
  // its AVX2 build where the CPU has it) on the rows of Q: (k, 4, 4) frames, for the test that
  // they are fk's bits.
  m.def(
      "fk_few",
      [](const Chain& chain, py::handle q_obj) {
        Array a = as_array(q_obj, "Q");
        if (a.ndim() != 2 || a.shape(1) != chain.dof() || a.shape(0) > Chain::kFkFew)
          fail("Q: expected shape (k, dof) with k <= 8, got " + shape_of(a));
        const int count = static_cast<int>(a.shape(0));
        Rigid F[Chain::kFkFew];
        chain.fk_few(a.data(), count, F);
        return frames_of(F, count);
      },
      py::arg("chain"), py::arg("Q"));
  // Chain::fk_few_turns on the rows of Q and their turns (C, S: cosines and sines, Q's shape).
  m.def(
      "fk_few_turns",
      [](const Chain& chain, py::handle q_obj, py::handle c_obj, py::handle s_obj) {
        Array q = as_array(q_obj, "Q"), c = as_array(c_obj, "C"), s = as_array(s_obj, "S");
        if (q.ndim() != 2 || q.shape(1) != chain.dof() || q.shape(0) > Chain::kFkFew)
          fail("Q: expected shape (k, dof) with k <= 8, got " + shape_of(q));
        if (shape_of(c) != shape_of(q) || shape_of(s) != shape_of(q)) fail("C, S: expected Q's shape");
        const int count = static_cast<int>(q.shape(0));
        Rigid F[Chain::kFkFew];
        chain.fk_few_turns(q.data(), c.data(), s.data(), count, F);
        return frames_of(F, count);
      },
      py::arg("chain"), py::arg("Q"), py::arg("C"), py::arg("S"));
  using testing::KdlIkReference;
  py::class_<KdlIkReference>(m, "KdlIk", "Reference for benchmarks: KDL's ChainIkSolverPos_LMA / _NR_JL.")
      .def(py::init([](const Chain& chain, const std::string& solver, int max_iter, double eps) {
             if (max_iter < 1) fail("max_iter: must be at least 1");
             if (!(eps > 0)) fail("eps: must be positive");
             return std::make_unique<KdlIkReference>(chain, solver, max_iter, eps);
           }),
           py::arg("chain"), py::arg("solver") = "lma", py::arg("max_iter") = 500, py::arg("eps") = 1e-5)
      .def(
          "solve",
          [](KdlIkReference& k, py::handle target, py::handle q0_obj) {
            const Rigid T = Rigid::from_matrix(as_transform(target, "target"));
            const Vector q0 = as_vector(q0_obj, "q0", k.dof());
            Vector q;
            const int code = k.solve(T, q0, q);
            return py::make_tuple(to_numpy(q), code);
          },
          py::arg("target"), py::arg("q0"), "(q, KDL error code) for one target.");
}

}  // namespace
}  // namespace robokin::bind

PYBIND11_MODULE(_testing, m) {
  m.doc() = "Hooks for robokin's tests and references for its benchmarks; not part of the API.";
  pybind11::module_::import("robokin._core");  // its Chain type and exception translators
  robokin::bind::bind_hooks(m);
  robokin::bind::bind_references(m);
  robokin::bind::bind_subproblem_hooks(m);
}
