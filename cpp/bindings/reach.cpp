// The Reach loop and path tracking (seed 000, Algorithm 1).
#include "arrays.hpp"
#include "bindings.hpp"
#include "progress.hpp"
#include "targets.hpp"

#include "robokin/reach.hpp"

#include <cmath>
#include <cstdio>

namespace robokin::bind {
namespace {

struct TrackResult {
  py::array_t<double> q, error;
  py::array_t<bool> converged;
  py::array_t<int> iterations;
};

ReachOptions make_options(const Chain& chain, int max_iter, double tol, double gain, double dt, bool saturate,
                          py::handle nullspace, double damping) {
  ReachOptions o;
  o.max_iter = max_iter;
  o.tol = tol;
  o.gain = gain;
  o.dt = dt;
  o.saturate = saturate;
  o.damping = damping;
  if (py::isinstance<py::str>(nullspace)) {
    if (py::cast<std::string>(nullspace) != "joint_limits")
      fail("nullspace: expected None, 'joint_limits' or an array of gains, got '" +
           py::cast<std::string>(nullspace) + "'");
    o.nullspace_weights = joint_limit_weights(chain);
  } else if (!nullspace.is_none()) {
    o.nullspace_weights = as_vector(nullspace, "nullspace", chain.dof());
  }
  check_reach_options(chain, o);
  return o;
}

ReachResult reach(const Chain& chain, py::handle target, py::handle q_obj, const std::string& task_str,
                  int max_iter, double tol, double gain, double dt, bool saturate, py::handle nullspace,
                  double damping) {
  const Task task = parse_task(task_str);
  const Target t = one_target(task, target);
  const Vector q = as_vector(q_obj, "q", chain.dof());
  Reacher reacher(chain, task, make_options(chain, max_iter, tol, gain, dt, saturate, nullspace, damping));
  ReachResult r = reacher.reach(t, q);
  // Finite inputs near 1e308 can still give an error beyond the largest double: no inf returned.
  if (!std::isfinite(r.error)) fail("target: the task error is not finite (the target is too far away)");
  return r;
}

TrackResult track(const Chain& chain, py::handle points, py::handle q0_obj, const std::string& task_str,
                  int max_iter, double tol, double gain, double dt, bool saturate, py::handle nullspace,
                  double damping) {
  const Task task = parse_task(task_str);
  const std::vector<Target> targets = many_targets(task, points, "points");
  const Vector q0 = as_vector(q0_obj, "q0", chain.dof());
  Reacher reacher(chain, task, make_options(chain, max_iter, tol, gain, dt, saturate, nullspace, damping));
  const auto count = static_cast<py::ssize_t>(targets.size());
  TrackResult r{py::array_t<double>({count, static_cast<py::ssize_t>(chain.dof())}),
                py::array_t<double>(count), py::array_t<bool>(count), py::array_t<int>(count)};
  double *q = r.q.mutable_data(), *err = r.error.mutable_data();
  bool* conv = r.converged.mutable_data();
  int* iters = r.iterations.mutable_data();
  PythonProgress progress("track");
  {
    py::gil_scoped_release release;
    reacher.track(targets.data(), count, q0, q, err, conv, iters, &progress);
  }
  if (!all_finite(err, count)) fail("points: the task error is not finite (a point is too far away)");
  return r;
}

std::string repr(const ReachResult& r) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "ReachResult(converged=%s, iterations=%d, error=%.3g, q=",
                r.converged ? "True" : "False", r.iterations, r.error);
  return buf + py::repr(to_numpy(r.q)).cast<std::string>() + ")";
}

}  // namespace

void bind_reach(py::module_& m) {
  py::class_<ReachResult>(m, "ReachResult", "What one Reach call did.")
      .def_property_readonly("q", [](const ReachResult& r) { return to_numpy(r.q); }, "Joints at the end.")
      .def_readonly("converged", &ReachResult::converged, "True when the task error is below tol.")
      .def_readonly("iterations", &ReachResult::iterations, "Iterations run.")
      .def_readonly("error", &ReachResult::error, "Norm of the task error at q.")
      .def(py::pickle(  // (version, q, converged, iterations, error)
          [](const ReachResult& r) { return py::make_tuple(kStateVersion, to_numpy(r.q), r.converged, r.iterations, r.error); },
          [](const py::tuple& t) {
            check_state(t, 5, "ReachResult");
            return ReachResult{as_vector(t[1], "q", -1, false), t[2].cast<bool>(), t[3].cast<int>(), t[4].cast<double>()};
          }))
      .def("__repr__", &repr);
  py::class_<TrackResult>(m, "TrackResult", "What tracking a path did, one row per path point.")
      .def_readonly("q", &TrackResult::q, "(K, dof) joints after each point.")
      .def_readonly("error", &TrackResult::error, "(K,) task error after each point.")
      .def_readonly("converged", &TrackResult::converged, "(K,) True where the point was reached within tol.")
      .def_readonly("iterations", &TrackResult::iterations, "(K,) Reach iterations per point.")
      .def(py::pickle(  // (version, q, error, converged, iterations)
          [](const TrackResult& r) { return py::make_tuple(kStateVersion, r.q, r.error, r.converged, r.iterations); },
          [](const py::tuple& t) {
            check_state(t, 5, "TrackResult");
            return TrackResult{py::array_t<double>(t[1]).attr("copy")(), py::array_t<double>(t[2]).attr("copy")(),
                               py::array_t<bool>(t[3]).attr("copy")(), py::array_t<int>(t[4]).attr("copy")()};
          }))
      .def("__repr__", [](const TrackResult& r) {
        const long n = r.error.size();
        long ok = 0;
        double worst = 0;
        for (long k = 0; k < n; ++k) ok += r.converged.data()[k], worst = std::max(worst, r.error.data()[k]);
        char buf[160];
        std::snprintf(buf, sizeof buf, "TrackResult(points=%ld, converged=%ld/%ld, max_error=%.3g)", n, ok, n, worst);
        return std::string(buf);
      });
  m.def("reach", &reach, py::arg("chain"), py::arg("target"), py::arg("q"), py::arg("task") = "xy",
        py::arg("max_iter") = 25, py::arg("tol") = 1e-5, py::arg("gain") = 0.75, py::arg("dt") = 0.025,
        py::arg("saturate") = true, py::arg("nullspace") = py::none(), py::arg("damping") = 0.0,
        "One Reach call (seed 000, Algorithm 1). Use robokin.reach, which also warns.");
  m.def("track", &track, py::arg("chain"), py::arg("points"), py::arg("q0"), py::arg("task") = "xy",
        py::arg("max_iter") = 25, py::arg("tol") = 1e-5, py::arg("gain") = 0.75, py::arg("dt") = 0.025,
        py::arg("saturate") = true, py::arg("nullspace") = py::none(), py::arg("damping") = 0.0,
        "Reach every point of a path in turn. Use robokin.track, which also warns.");
  m.def(
      "joint_limit_cost",
      [](const Chain& chain, py::handle q_obj) -> py::object {
        Array q = as_array(q_obj, "q");
        const long n = chain.dof();
        if (!((q.ndim() == 1 && q.shape(0) == n) || (q.ndim() == 2 && q.shape(1) == n)))
          fail("q: expected shape (" + std::to_string(n) + ",) or (N, " + std::to_string(n) + "), got " + shape_of(q));
        require_finite(q.data(), q.size(), "q");
        py::array_t<double> out(q.ndim() == 1 ? 1 : q.shape(0));
        for (py::ssize_t k = 0; k < out.size(); ++k) out.mutable_data()[k] = joint_limit_cost(chain, q.data() + k * n);
        // A finite q far outside the limits (near 1e300) squares to inf: say so rather than return it.
        if (!all_finite(out.data(), out.size())) fail("q: the cost is not finite (q is too far from the limits)");
        if (q.ndim() == 1) return py::float_(out.data()[0]);
        return std::move(out);
      },
      py::arg("chain"), py::arg("q"),
      "Seed 000's joint-limit cost z = 1/2 |W (qbar - q)|^2, W = diag(1 / (q_max - q_min)) (0 for an\n"
      "unlimited joint): a float for q (dof,), an array (N,) for a batch (N, dof).");
}

}  // namespace robokin::bind
