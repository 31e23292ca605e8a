// Numerical inverse kinematics (use robokin.ik / robokin.ik_batch) and KDL's solvers as references.
#include "arrays.hpp"
#include "bindings.hpp"
#include "progress.hpp"
#include "targets.hpp"

#include "robokin/ik.hpp"

#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>

namespace robokin::bind {
namespace {

struct BatchResult {
  py::array_t<double> q, error_p, error_r;
  py::array_t<bool> success;
  py::array_t<int> iterations, attempts;
};

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

// An int argument (anything with __index__, not a bool) in [lo, hi]; the message names it.
int int_arg(py::handle obj, const char* name, long long lo, long long hi, const char* why) {
  if (py::isinstance<py::bool_>(obj) || !PyIndex_Check(obj.ptr())) fail(std::string(name) + ": expected an int");
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(obj.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
  if (overflow < 0 || (!overflow && v < lo)) fail(std::string(name) + ": must be >= " + std::to_string(lo));
  if (overflow > 0 || v > hi) fail(std::string(name) + ": must be at most " + std::to_string(hi) + why);
  return static_cast<int>(v);
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

// An optional number (None handled by the caller): a string or a list is a ValueError naming it,
// not pybind11's RuntimeError "Unable to cast".
double number_arg(py::handle obj, const char* name) {
  try {
    return py::cast<double>(obj);
  } catch (const py::cast_error&) {
    fail(std::string(name) + ": expected None or a number");
  }
}

// Whether a solve may take long enough for the GIL to be worth releasing (a timeout, or more than
// ~1700 iterations in all): short solves keep it (releasing costs more than they do).
bool may_be_long(const IkOptions& o) {
  return o.timeout > 1e-3 || (static_cast<long long>(o.restarts) + 1) * o.max_iter > 1700;
}

// The options of a call. Left out (None), `restarts` and `timeout` are IkOptions{}'s: restarts
// until success within the default time budget. An explicit `restarts` keeps its contract from
// before the defaults had a budget: that many restarts, no time budget unless `timeout` is given.
IkOptions options_arg(const std::string& method, const std::string& task, double tol_p, double tol_r, int max_iter,
                      py::handle restarts, py::handle timeout, py::handle damping) {
  IkOptions o;
  o.method = parse_ik_method(method);
  o.task = parse_task(task);
  if (!(tol_p > 0) || !std::isfinite(tol_p)) fail("tol_p: must be a positive number");
  if (!(tol_r > 0) || !std::isfinite(tol_r)) fail("tol_r: must be a positive number");
  if (max_iter < 1) fail("max_iter: must be at least 1");
  o.tol_p = tol_p;
  o.tol_r = o.task == Task::Pose || o.task == Task::XYPhi ? tol_r : INFINITY;
  o.max_iter = max_iter;
  if (!restarts.is_none()) {
    o.restarts = int_arg(restarts, "restarts", 0, kMaxRestarts, " (use timeout to bound the time)");
    o.timeout = 0.0;  // no budget unless one is given
  }
  if (!timeout.is_none()) {
    const double t = number_arg(timeout, "timeout");
    if (!(t > 0) || !std::isfinite(t)) fail("timeout: must be None or a positive number of seconds");
    o.timeout = t;
  }
  if (!damping.is_none()) {
    const double d = number_arg(damping, "damping");
    if (!(d > 0) || !std::isfinite(d)) fail("damping: must be None or a positive number");
    o.damping = d;
  } else {
    o.damping = default_damping(o.method);  // the C++ default, the one source of truth
  }
  return o;
}

IkResult ik(const Chain& chain, py::handle target, py::handle q0_obj, const std::string& method,
            const std::string& task, double tol_p, double tol_r, int max_iter, py::handle restarts, py::handle seed,
            py::handle timeout, py::handle damping) {
  const IkOptions o = options_arg(method, task, tol_p, tol_r, max_iter, restarts, timeout, damping);
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

BatchResult ik_batch_py(const Chain& chain, py::handle targets_obj, py::handle q0_obj, const std::string& method,
                        const std::string& task, double tol_p, double tol_r, int max_iter, py::handle restarts,
                        py::handle seed, py::handle timeout, py::handle damping, bool path) {
  IkOptions o = options_arg(method, task, tol_p, tol_r, max_iter, restarts, timeout, damping);
  if (path && restarts.is_none()) {
    // A path warm-starts each target from the previous solution: a random restart could land on
    // another branch (a jump of the joints between neighbouring points), so by default it does not
    // restart (restarts=k allows it).
    o.restarts = 0;
    if (timeout.is_none()) o.timeout = 0.0;
  }
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
  const auto N = static_cast<py::ssize_t>(count);
  BatchResult r{py::array_t<double>({N, static_cast<py::ssize_t>(n)}), py::array_t<double>(N),
                py::array_t<double>(N), py::array_t<bool>(N), py::array_t<int>(N), py::array_t<int>(N)};
  double *q = r.q.mutable_data(), *ep = r.error_p.mutable_data(), *er = r.error_r.mutable_data();
  bool* success = r.success.mutable_data();
  int *it = r.iterations.mutable_data(), *at = r.attempts.mutable_data();
  PythonProgress progress("ik_batch");
  {
    py::gil_scoped_release release;
    robokin::ik_batch(chain, o, targets.data(), count, q0.data(), q0_stride, path, s, q, success, it, at, ep, er,
                      &progress);
  }
  require_finite_errors(ep, er, count, "targets");
  return r;
}

// A solver bound to a chain and options: the per-call cost is the target and q0 only.
struct BoundSolver {
  py::object owner;  // the Python Chain, kept alive
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

// Pickling: versioned state tuples (the result types, and IKSolver with its chain and options).
std::unique_ptr<BoundSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 13, "IKSolver");
  IkOptions o;
  o.method = parse_ik_method(t[2].cast<std::string>());
  o.task = parse_task(t[3].cast<std::string>());
  o.tol_p = t[4].cast<double>();
  o.tol_r = t[5].cast<double>();
  o.max_iter = t[6].cast<int>();
  o.restarts = t[7].cast<int>();
  o.timeout = t[8].cast<double>();
  o.damping = t[9].cast<double>();
  if (!(o.tol_p > 0) || !(o.tol_r > 0) || o.max_iter < 1 || o.restarts < 0 || o.restarts > kMaxRestarts ||
      !(o.timeout >= 0) || !(o.damping >= 0))
    fail("IKSolver state: options out of range");
  return std::make_unique<BoundSolver>(py::reinterpret_borrow<py::object>(t[1]), o, t[10].cast<bool>(),
                                       t[11].cast<std::uint64_t>(), t[12].cast<std::uint64_t>());
}

std::string repr(const IkResult& r) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "IKResult(success=%s, iterations=%d, attempts=%d, error_p=%.3g m, error_r=%.3g rad, q=",
                r.success ? "True" : "False", r.iterations, r.attempts, r.error_p, r.error_r);
  return buf + py::repr(to_numpy(r.q)).cast<std::string>() + ")";
}

}  // namespace

void bind_ik(py::module_& m) {
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
      .def(py::pickle(
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
      .def("__repr__", &repr);
  py::class_<BatchResult>(m, "IKBatchResult", "What ik_batch found, one row per target.")
      .def_readonly("q", &BatchResult::q, "(N, dof) joints.")
      .def_readonly("success", &BatchResult::success, "(N,) verified successes.")
      .def_readonly("iterations", &BatchResult::iterations, "(N,) iterations.")
      .def_readonly("attempts", &BatchResult::attempts, "(N,) attempts (1 + restarts used).")
      .def_readonly("error_p", &BatchResult::error_p, "(N,) position errors (m).")
      .def_readonly("error_r", &BatchResult::error_r, "(N,) orientation errors (rad).")
      .def("__len__", [](const BatchResult& r) { return r.success.size(); })
      .def(py::pickle(
          [](const BatchResult& r) {
            return py::make_tuple(kStateVersion, r.q, r.success, r.iterations, r.attempts, r.error_p, r.error_r);
          },
          [](const py::tuple& t) {
            check_state(t, 7, "IKBatchResult");
            // Copies, so that the result owns its arrays as one made by ik_batch does.
            return BatchResult{py::array_t<double>(t[1]).attr("copy")(), py::array_t<double>(t[5]).attr("copy")(),
                               py::array_t<double>(t[6]).attr("copy")(), py::array_t<bool>(t[2]).attr("copy")(),
                               py::array_t<int>(t[3]).attr("copy")(), py::array_t<int>(t[4]).attr("copy")()};
          }))
      .def("__repr__", [](const BatchResult& r) {
        const long n = r.success.size();
        long ok = 0;
        double worst_p = 0, worst_r = 0;
        for (long k = 0; k < n; ++k) {
          ok += r.success.data()[k];
          worst_p = std::max(worst_p, r.error_p.data()[k]);
          worst_r = std::max(worst_r, r.error_r.data()[k]);
        }
        char buf[200];
        std::snprintf(buf, sizeof buf, "IKBatchResult(targets=%ld, success=%ld/%ld, max_error_p=%.3g m, max_error_r=%.3g rad)",
                      n, ok, n, worst_p, worst_r);
        return std::string(buf);
      });
  // Every default below is IkOptions{}'s (restarts and timeout: None selects it).
  const IkOptions d;
  const std::string method_d = ik_method_name(d.method), task_d = task_name(d.task);
  py::dict defaults;
  defaults["method"] = method_d;
  defaults["task"] = task_d;
  defaults["tol_p"] = d.tol_p;
  defaults["tol_r"] = d.tol_r;
  defaults["max_iter"] = d.max_iter;
  defaults["restarts"] = d.restarts;
  defaults["timeout"] = d.timeout;
  m.attr("IK_DEFAULTS") = py::module_::import("types").attr("MappingProxyType")(defaults);
  m.def("ik", &ik, py::arg("chain"), py::arg("target"), py::arg("q0"), py::arg("method") = method_d,
        py::arg("task") = task_d, py::arg("tol_p") = d.tol_p, py::arg("tol_r") = d.tol_r,
        py::arg("max_iter") = d.max_iter, py::arg("restarts") = py::none(), py::arg("seed") = py::none(),
        py::arg("timeout") = py::none(), py::arg("damping") = py::none(), "Numerical IK. Use robokin.ik.");
  m.def("ik_batch", &ik_batch_py, py::arg("chain"), py::arg("targets"), py::arg("q0"), py::arg("method") = method_d,
        py::arg("task") = task_d, py::arg("tol_p") = d.tol_p, py::arg("tol_r") = d.tol_r,
        py::arg("max_iter") = d.max_iter, py::arg("restarts") = py::none(), py::arg("seed") = py::none(),
        py::arg("timeout") = py::none(), py::arg("damping") = py::none(), py::arg("path") = false,
        "Numerical IK of many targets. Use robokin.ik_batch.");
  m.def(
      "_hessian_times",
      [](const Chain& chain, py::handle q_obj, py::handle a_obj) {
        const Vector q = as_vector(q_obj, "q", chain.dof()), a = as_vector(a_obj, "a", chain.dof());
        Matrix6X J6(6, chain.dof()), out;
        Rigid T;
        chain.fk_jacobian(q.data(), T, J6.data());
        hessian_times(chain, J6, a, out);
        return to_numpy(out);
      },
      py::arg("chain"), py::arg("q"), py::arg("a"), "sum_j a_j dJ/dq_j (6, dof): Halley's kinematic Hessian term.");
  py::class_<BoundSolver>(m, "IKSolver",
                          "A numerical IK solver bound to a chain and options (robokin.ik's arguments):\n"
                          "solve(target, q0) costs only the solve. Call k of a seeded solver uses seed + k.\n"
                          "Like robokin.ik, solve releases the GIL when it may be long (a timeout, or more than\n"
                          "~1700 iterations in all); calls from several threads are serialised: one solver per\n"
                          "thread for parallel solves (ik_batch is the parallel route).")
      .def(py::init([](const Chain& chain, const std::string& method, const std::string& task, double tol_p,
                       double tol_r, int max_iter, py::handle restarts, py::handle seed, py::handle timeout,
                       py::handle damping) {
             return std::make_unique<BoundSolver>(
                 py::cast(chain, py::return_value_policy::reference),  // the caller's Chain object (registered)
                 options_arg(method, task, tol_p, tol_r, max_iter, restarts, timeout, damping), !seed.is_none(),
                 seed_arg(seed));
           }),
           py::arg("chain"), py::arg("method") = method_d, py::arg("task") = task_d, py::arg("tol_p") = d.tol_p,
           py::arg("tol_r") = d.tol_r, py::arg("max_iter") = d.max_iter, py::arg("restarts") = py::none(),
           py::arg("seed") = py::none(), py::arg("timeout") = py::none(), py::arg("damping") = py::none(),
           py::keep_alive<1, 2>())
      .def(py::pickle(
          // (version, chain, method, task, tol_p, tol_r, max_iter, restarts, timeout, damping, seeded, seed, calls)
          [](const BoundSolver& b) {
            const IkOptions& o = b.options;
            return py::make_tuple(kStateVersion, b.owner, ik_method_name(o.method), task_name(o.task), o.tol_p,
                                  o.tol_r, o.max_iter, o.restarts, o.timeout, o.damping, b.seeded, b.seed, b.calls);
          },
          [](const py::tuple& t) { return solver_from_state(t); }))
      .def("solve", &BoundSolver::solve, py::arg("target"), py::arg("q0"), "Solves one target from q0 -> IKResult.")
      .def_property_readonly("method", [](const BoundSolver& b) { return ik_method_name(b.options.method); })
      .def_property_readonly("task", [](const BoundSolver& b) { return task_name(b.options.task); })
      .def("__repr__", [](const BoundSolver& b) {
        char buf[200];
        char timeout[32] = "None";
        if (b.options.timeout > 0) std::snprintf(timeout, sizeof timeout, "%g", b.options.timeout);
        std::snprintf(buf, sizeof buf,
                      "IKSolver(method='%s', task='%s', tol_p=%g, tol_r=%g, max_iter=%d, restarts=%d, timeout=%s)",
                      ik_method_name(b.options.method), task_name(b.options.task), b.options.tol_p, b.options.tol_r,
                      b.options.max_iter, b.options.restarts, timeout);
        return std::string(buf);
      });
  py::class_<KdlIkReference>(m, "_KdlIk", "Reference for benchmarks: KDL's ChainIkSolverPos_LMA / _NR_JL.")
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

}  // namespace robokin::bind
