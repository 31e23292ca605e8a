// Numerical inverse kinematics (use robokin.ik / robokin.ik_batch) and KDL's solvers as references.
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"
#include "targets.hpp"

#include "robokin/ik.hpp"

#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
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
  if (py::isinstance<py::bool_>(seed) || !PyIndex_Check(seed.ptr())) fail_kind("seed: expected None or an int");
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

IkResult ik(const Chain& chain, ArrayLike target, ArrayLike q0_obj, SeedLike seed, const py::kwargs& kwargs) {
  const auto o = options_arg<IkOptions>(kwargs);
  const Target t = one_target(chain, o.task_for(chain), target);
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  const std::uint64_t s = seed_arg(seed);
  // One solver per thread, kept between calls: no workspace allocation per solve.
  thread_local IkSolver solver(chain, o);
  solver.reset(chain, o);
  const auto solve = [&](Progress* progress) { return solver.solve(t, q0.data(), s, progress); };
  return checked(may_be_long(o) ? released("ik", solve) : solve(nullptr));
}

IkBatchResult ik_batch_py(const Chain& chain, ArrayLike targets_obj, ArrayLike q0_obj, SeedLike seed, bool path,
                          const py::kwargs& kwargs) {
  const auto o = options_arg<IkOptions>(kwargs);
  const int n = chain.dof();
  const std::vector<Target> targets = many_targets(chain, o.task_for(chain), targets_obj, "targets", "N");
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
  const IkBatchResult r = released("ik_batch", [&](Progress* progress) {
    return robokin::ik_batch(chain, o, targets.data(), count, q0.data(), q0_stride, path, s, progress);
  });
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

  // The options are kept with their task resolved (task None: the chain's natural task).
  BoundSolver(py::object c, const IkOptions& o, bool seeded_, std::uint64_t seed_, std::uint64_t calls_ = 0)
      : owner(std::move(c)), chain(&owner.cast<const Chain&>()), options(resolved(o, *chain)), solver(*chain, options),
        seeded(seeded_), seed(seed_), calls(calls_) {}

  static IkOptions resolved(IkOptions o, const Chain& chain) {
    o.task = o.task_for(chain);
    return o;
  }

  IkResult solve(ArrayLike target, ArrayLike q0_obj) {
    const Target t = one_target(*chain, *options.task, target);
    const Vector q0 = as_vector(q0_obj, "q0", chain->dof());
    const std::uint64_t s = seeded ? seed + calls++ : seed_arg(py::none());
    // The lock is taken inside: without the GIL when it is released (no deadlock with a solve in progress).
    const auto solve = [&](Progress* progress) {
      std::lock_guard<std::mutex> lock(busy);
      return solver.solve(t, q0.data(), s, progress);
    };
    return checked(may_be_long(options) ? released("IKSolver.solve", solve) : solve(nullptr));
  }
};

// Pickling: a versioned state tuple (check_state, arrays.hpp).
std::unique_ptr<BoundSolver> solver_from_state(const py::tuple& t) {
  check_state(t, 6, "IKSolver");  // (version, chain, options, seeded, seed, calls)
  const IkOptions o = t[2].cast<IkOptions>();
  o.validate();
  return std::make_unique<BoundSolver>(py::reinterpret_borrow<py::object>(t[1]), o, t[3].cast<bool>(),
                                       t[4].cast<std::uint64_t>(), t[5].cast<std::uint64_t>());
}

}  // namespace

void bind_ik(py::module_& m) {
  OptionsClass<IkOptions>(m, "IKOptions", "The options of a numerical IK solve (robokin.ik's keywords); None: the default rule.")
      .fields();
  ResultClass<IkResult>(m, "IKResult", "What one numerical IK solve found.", false)
      .fields()
      .done_with([](py::class_<IkResult>& c) { c.def("__bool__", [](const IkResult& r) { return r.success; }); });
  ResultClass<IkBatchResult>(m, "IKBatchResult", "What ik_batch found, one row per target (read-only arrays).", true)
      .fields()
      .done();
  // The defaults as a solve resolves them (restarts and timeout None: until success within the
  // default time budget, IkOptions).
  const IkOptions d;
  py::dict defaults;
  const py::object fields = py::cast(d);
  for (const std::string& name : field_names<IkOptions>()) defaults[name.c_str()] = fields.attr(name.c_str());
  defaults["restarts"] = d.max_restarts();
  defaults["timeout"] = d.budget();
  defaults.attr("pop")("damping");  // None: the method's (default_damping)
  m.attr("IK_DEFAULTS") = py::module_::import("types").attr("MappingProxyType")(defaults);
  // seed may come by position: a call with no keyword takes pybind11's quicker route (robokin.ik
  // passes it so).
  m.def("ik", &ik, py::arg("chain"), py::arg("target"), py::arg("q0"), py::arg("seed") = py::none(),
        "Numerical IK; options as keywords (IKOptions). Use robokin.ik.");
  m.def("ik_batch", &ik_batch_py, py::arg("chain"), py::arg("targets"), py::arg("q0"), py::kw_only(),
        py::arg("seed") = py::none(), py::arg("path") = false,
        "Numerical IK of many targets; options as keywords (IKOptions). Use robokin.ik_batch.");
  py::class_<BoundSolver> solver(m, "IKSolver",
                          "A numerical IK solver bound to a chain and options (robokin.ik's arguments):\n"
                          "solve(target, q0) costs only the solve. Call k of a seeded solver uses seed + k.\n"
                          "Like robokin.ik, solve releases the GIL when it may be long (a timeout, or more than\n"
                          "~1700 iterations in all); calls from several threads are serialised: one solver per\n"
                          "thread for parallel solves (ik_batch is the parallel route).");
  static const std::string init_doc =
      kwargs_doc<IkOptions>("IKSolver(chain, *, seed=None", "The solver of chain with these options.");
  solver.def(py::init([](const Chain& chain, SeedLike seed, const py::kwargs& kwargs) {
             return std::make_unique<BoundSolver>(py::cast(chain, py::return_value_policy::reference),  // the caller's
                                                  options_arg<IkOptions>(kwargs), !seed.is_none(), seed_arg(seed));
           }),
           py::arg("chain"), py::kw_only(), py::arg("seed") = py::none(), py::keep_alive<1, 2>(), init_doc.c_str())
      .def("solve", &BoundSolver::solve, py::arg("target"), py::arg("q0"), "Solves one target from q0 -> IKResult.")
      .def_property_readonly("method", [](const BoundSolver& b) { return name_of(b.options.method); })
      .def_property_readonly("task", [](const BoundSolver& b) { return task_name(*b.options.task); },
                             "The task solved for (task=None: the chain's natural_task).")
      .def_property_readonly("options", [](const BoundSolver& b) { return b.options; },
                             "The solver's IKOptions (a copy), its task resolved (None: the chain's natural_task).")
      .def(py::pickle(  // (version, chain, options, seeded, seed, calls): a copy continues the seed sequence
          [](const BoundSolver& b) {
            return py::make_tuple(kStateVersion, b.owner, b.options, b.seeded, b.seed, b.calls);
          },
          &solver_from_state))
      .def("__repr__", [](py::handle self) { return printed("ik_solver_repr", self); });
}

}  // namespace robokin::bind
