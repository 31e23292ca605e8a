// Numerical inverse kinematics (use robokin.ik / robokin.ik_batch) and KDL's solvers as references.
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "targets.hpp"

#include "robokin/ik.hpp"

#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

namespace robokin::bind {
namespace {

std::uint64_t seed_arg(py::handle seed) {
  if (seed.is_none()) {
    // A fresh seed per call, cheaply: splitmix64 of a counter mixed with the clock.
    static std::atomic<std::uint64_t> counter{0};
    std::uint64_t z = counter.fetch_add(0x9E3779B97F4A7C15ull) +
                      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Any int (or object with __index__, such as numpy's integers) but a bool.
  if (py::isinstance<py::bool_>(seed) || !PyIndex_Check(seed.ptr())) fail("seed: expected None or an int");
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(seed.ptr()));
  if (!index) throw py::error_already_set();
  const unsigned long long v = PyLong_AsUnsignedLongLong(index.ptr());
  if (v == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
    PyErr_Clear();
    fail("seed: expected an int in [0, 2**64)");
  }
  return static_cast<std::uint64_t>(v);
}

// Finite targets near 1e308 can still be farther from the tool than the largest double: a
// ValueError naming the target rather than an infinite error in the result.
void require_finite_errors(const double* error_p, const double* error_r, long count, const char* name) {
  if (!all_finite(error_p, count) || !all_finite(error_r, count))
    fail(std::string(name) + ": the error is not finite (the target is too far away)");
}

IkResult checked(IkResult r) {
  require_finite_errors(&r.error_p, &r.error_r, 1, "target");
  return r;
}

// Whether a solve may take long enough for the GIL to be worth releasing (a timeout, or more than
// ~1700 iterations in all): short solves keep it (releasing costs more than they do).
bool may_be_long(const IkOptions& o) {
  return o.budget() > 1e-3 || (static_cast<long long>(o.max_restarts()) + 1) * o.max_iter > 1700;
}

using IkOptionsClass = OptionsClass<IkOptions>;

// The options of a call: the keyword arguments (IkOptions' fields), validated.
IkOptions options_arg(const py::kwargs& kwargs) {
  IkOptions o = IkOptionsClass::from_kwargs(kwargs);
  o.validate();
  return o;
}

IkResult ik(const Chain& chain, py::handle target, py::handle q0_obj, py::handle seed, const py::kwargs& kwargs) {
  const IkOptions o = options_arg(kwargs);
  const Target t = one_target(o.task, target);
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  const std::uint64_t s = seed_arg(seed);
  // One solver per thread, kept between calls: no workspace allocation per solve.
  thread_local IkSolver solver(chain, o);
  solver.reset(chain, o);
  IkResult r;
  if (may_be_long(o)) {
    PythonProgress progress("ik");
    py::gil_scoped_release release;
    r = solver.solve(t, q0.data(), s, &progress);
  } else {
    r = solver.solve(t, q0.data(), s);
  }
  return checked(r);
}

IkBatchResult ik_batch_py(const Chain& chain, py::handle targets_obj, py::handle q0_obj, py::handle seed, bool path,
                          const py::kwargs& kwargs) {
  const IkOptions o = options_arg(kwargs);
  const int n = chain.dof();
  const std::vector<Target> targets = many_targets(o.task, targets_obj, "targets", "N");
  const long count = static_cast<long>(targets.size());
  Array q0 = as_array(q0_obj, "q0");
  long q0_stride;
  if (q0.ndim() == 1 && q0.shape(0) == n) {
    q0_stride = 0;
  } else if (q0.ndim() == 2 && q0.shape(0) == count && q0.shape(1) == n && !path) {
    q0_stride = n;
  } else {
    fail("q0: expected shape (" + std::to_string(n) + ",)" +
         (path ? std::string(" (path=True starts from one configuration)")
               : " or (" + std::to_string(count) + ", " + std::to_string(n) + ")") +
         ", got " + shape_of(q0));
  }
  require_finite(q0.data(), q0.size(), "q0");
  const std::uint64_t s = seed_arg(seed);
  PythonProgress progress("ik_batch");
  IkBatchResult r;
  {
    py::gil_scoped_release release;
    r = robokin::ik_batch(chain, o, targets.data(), count, q0.data(), q0_stride, path, s, &progress);
  }
  require_finite_errors(r.error_p.data(), r.error_r.data(), count, "targets");
  return r;
}

// A solver bound to a chain and options: the per-call cost is the target and q0 only.
struct BoundSolver {
  py::object owner;  // the Python Chain, kept alive (also in a solver unpickled with its chain)
  const Chain* chain;
  IkOptions options;
  IkSolver solver;
  bool seeded = false;
  std::uint64_t seed = 0, calls = 0;
  std::mutex busy;  // the GIL may be released during a solve: one solve at a time

  BoundSolver(py::object c, const IkOptions& o, bool seeded_, std::uint64_t seed_, std::uint64_t calls_ = 0)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()), options(o), solver(*chain, o), seeded(seeded_),
        seed(seed_), calls(calls_) {}

  IkResult solve(py::handle target, py::handle q0_obj) {
    const Target t = one_target(options.task, target);
    const Vector q0 = as_vector(q0_obj, "q0", chain->dof());
    const std::uint64_t s = seeded ? seed + calls++ : seed_arg(py::none());
    IkResult r;
    if (may_be_long(options)) {
      PythonProgress progress("IKSolver.solve");
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(busy);  // taken without the GIL: no deadlock with a solve in progress
      r = solver.solve(t, q0.data(), s, &progress);
    } else {
      std::lock_guard<std::mutex> lock(busy);
      r = solver.solve(t, q0.data(), s);
    }
    return checked(r);
  }
};

// Pickling: versioned state tuples (check_state, arrays.hpp).
std::unique_ptr<BoundSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 6, "IKSolver");  // (version, chain, options, seeded, seed, calls)
  const IkOptions o = t[2].cast<IkOptions>();
  o.validate();
  return std::make_unique<BoundSolver>(py::reinterpret_borrow<py::object>(t[1]), o, t[3].cast<bool>(),
                                       t[4].cast<std::uint64_t>(), t[5].cast<std::uint64_t>());
}

template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> state_array(py::handle obj, const char* name) {
  auto a = aligned_array<T>(obj);
  if (!a) fail(std::string(name) + ": expected an array in the state");
  return a;
}

IkBatchResult batch_from_state(const py::tuple& t) {
  check_state(t, 7, "IKBatchResult");  // (version, q, success, iterations, attempts, error_p, error_r)
  const auto q = state_array<double>(t[1], "q");
  const auto success = state_array<bool>(t[2], "success");
  const auto iterations = state_array<int>(t[3], "iterations"), attempts = state_array<int>(t[4], "attempts");
  const auto ep = state_array<double>(t[5], "error_p"), er = state_array<double>(t[6], "error_r");
  const py::ssize_t n = success.size();
  if (q.ndim() != 2 || q.shape(0) != n || iterations.size() != n || attempts.size() != n || ep.size() != n ||
      er.size() != n)
    fail("IKBatchResult state: arrays of different lengths");
  IkBatchResult r;
  r.q = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(q.data(), n, q.shape(1));
  r.success = Eigen::Map<const Eigen::Array<bool, Eigen::Dynamic, 1>>(success.data(), n);
  r.iterations = Eigen::Map<const Eigen::ArrayXi>(iterations.data(), n);
  r.attempts = Eigen::Map<const Eigen::ArrayXi>(attempts.data(), n);
  r.error_p = Eigen::Map<const Vector>(ep.data(), n);
  r.error_r = Eigen::Map<const Vector>(er.data(), n);
  return r;
}

}  // namespace

void bind_ik(py::module_& m) {
  IkOptionsClass(m, "IKOptions", "The options of a numerical IK solve (robokin.ik's keywords); None: the default rule.")
      .field_as<std::string>("method", [](const IkOptions& o) { return std::string(ik_method_name(o.method)); },
                             [](IkOptions& o, const std::string& v) { o.method = parse_ik_method(v); },
                             "'lm', 'gn', 'nr' or 'halley'.")
      .field_as<std::string>("task", [](const IkOptions& o) { return std::string(task_name(o.task)); },
                             [](IkOptions& o, const std::string& v) { o.task = parse_task(v); },
                             "'pose', 'position', 'xy' or 'xyphi'.")
      .field("tol_p", &IkOptions::tol_p, "Position tolerance (m).")
      .field("tol_r", &IkOptions::tol_r, "Orientation tolerance (rad); unused for tasks without orientation.")
      .field("max_iter", &IkOptions::max_iter, "Iterations per attempt.")
      .field("restarts", &IkOptions::restarts,
             "Extra attempts from random configurations, at most 1,000,000; None: as many as the time budget allows.")
      .field("timeout", &IkOptions::timeout,
             "CPU seconds for every attempt; None: 5 ms when restarts is None, else no budget.")
      .field("damping", &IkOptions::damping, "Damping (lm: initial mu; nr, halley: lambda); None: the method's.");
  py::class_<IkResult>(m, "IKResult", "What one numerical IK solve found.")
      .def_property_readonly("q", [](const IkResult& r) { return to_numpy(r.q); },
                             "(dof,) joints: the solution, or the best point found (within the limits).")
      .def_readonly("success", &IkResult::success,
                    "True when FK of q meets tol_p and tol_r (checked after wrapping and clamping).")
      .def_readonly("iterations", &IkResult::iterations, "Iterations over every attempt.")
      .def_readonly("attempts", &IkResult::attempts, "1 + the random restarts used.")
      .def_readonly("error_p", &IkResult::error_p, "Position error at q (m).")
      .def_readonly("error_r", &IkResult::error_r, "Orientation error at q (rad); 0 for tasks without one.")
      .def("__bool__", [](const IkResult& r) { return r.success; })
      .def(py::pickle(  // (version, q, success, iterations, attempts, error_p, error_r)
          [](const IkResult& r) {
            return py::make_tuple(kStateVersion, to_numpy(r.q), r.success, r.iterations, r.attempts, r.error_p,
                                  r.error_r);
          },
          [](const py::tuple& t) {
            check_state(t, 7, "IKResult");
            IkResult r;
            r.q = as_vector(t[1], "q", -1, false);
            r.success = t[2].cast<bool>();
            r.iterations = t[3].cast<int>();
            r.attempts = t[4].cast<int>();
            r.error_p = t[5].cast<double>();
            r.error_r = t[6].cast<double>();
            return r;
          }))
      .def("__repr__", [](py::handle self) {
        return repr_fields(self, {"success", "iterations", "attempts", "error_p", "error_r", "q"});
      });
  py::class_<IkBatchResult> batch(m, "IKBatchResult", "What ik_batch found, one row per target (read-only arrays).");
  def_array(batch, "q", &IkBatchResult::q, "(N, dof) joints.");
  def_array(batch, "success", &IkBatchResult::success, "(N,) verified successes.");
  def_array(batch, "iterations", &IkBatchResult::iterations, "(N,) iterations.");
  def_array(batch, "attempts", &IkBatchResult::attempts, "(N,) attempts (1 + restarts used).");
  def_array(batch, "error_p", &IkBatchResult::error_p, "(N,) position errors (m).");
  def_array(batch, "error_r", &IkBatchResult::error_r, "(N,) orientation errors (rad).");
  batch
      .def("__len__", [](const IkBatchResult& r) { return r.success.size(); })
      .def(py::pickle(
          [](py::handle self) {
            return py::make_tuple(kStateVersion, self.attr("q"), self.attr("success"), self.attr("iterations"),
                                  self.attr("attempts"), self.attr("error_p"), self.attr("error_r"));
          },
          &batch_from_state))
      .def("__repr__", [](py::handle self) {
        return repr_fields(self, {"q", "success", "iterations", "attempts", "error_p", "error_r"});
      });
  // The defaults as a solve resolves them (restarts and timeout None: until success within 5 ms).
  const IkOptions d;
  py::dict defaults;
  defaults["method"] = ik_method_name(d.method);
  defaults["task"] = task_name(d.task);
  defaults["tol_p"] = d.tol_p;
  defaults["tol_r"] = d.tol_r;
  defaults["max_iter"] = d.max_iter;
  defaults["restarts"] = d.max_restarts();
  defaults["timeout"] = d.budget();
  m.attr("IK_DEFAULTS") = py::module_::import("types").attr("MappingProxyType")(defaults);
  m.def("ik", &ik, py::arg("chain"), py::arg("target"), py::arg("q0"), py::kw_only(), py::arg("seed") = py::none(),
        "Numerical IK; options as keywords (IKOptions). Use robokin.ik.");
  m.def("ik_batch", &ik_batch_py, py::arg("chain"), py::arg("targets"), py::arg("q0"), py::kw_only(),
        py::arg("seed") = py::none(), py::arg("path") = false,
        "Numerical IK of many targets; options as keywords (IKOptions). Use robokin.ik_batch.");
  py::class_<BoundSolver>(m, "IKSolver",
                          "A numerical IK solver bound to a chain and options (robokin.ik's arguments):\n"
                          "solve(target, q0) costs only the solve. Call k of a seeded solver uses seed + k.\n"
                          "Like robokin.ik, solve releases the GIL when it may be long (a timeout, or more than\n"
                          "~1700 iterations in all); calls from several threads are serialised: one solver per\n"
                          "thread for parallel solves (ik_batch is the parallel route).")
      .def(py::init([](const Chain& chain, py::handle seed, const py::kwargs& kwargs) {
             return std::make_unique<BoundSolver>(py::cast(chain, py::return_value_policy::reference),  // the caller's
                                                  options_arg(kwargs), !seed.is_none(), seed_arg(seed));
           }),
           py::arg("chain"), py::kw_only(), py::arg("seed") = py::none(), py::keep_alive<1, 2>())
      .def("solve", &BoundSolver::solve, py::arg("target"), py::arg("q0"), "Solves one target from q0 -> IKResult.")
      .def_property_readonly("method", [](const BoundSolver& b) { return ik_method_name(b.options.method); })
      .def_property_readonly("task", [](const BoundSolver& b) { return task_name(b.options.task); })
      .def_property_readonly("options", [](const BoundSolver& b) { return b.options; }, "The solver's IKOptions (a copy).")
      .def(py::pickle(  // (version, chain, options, seeded, seed, calls): a copy continues the seed sequence
          [](const BoundSolver& b) {
            return py::make_tuple(kStateVersion, b.owner, b.options, b.seeded, b.seed, b.calls);
          },
          &solver_from_state))
      .def("__repr__", [](py::handle self) {
        const std::string options = py::repr(self.attr("options")).cast<std::string>();
        return "IKSolver" + options.substr(options.find('('));
      });
}

}  // namespace robokin::bind
