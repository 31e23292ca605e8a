// The dynamic programme of robokin.track_postures (use robokin.track_postures, which finds the
// solution sets and builds the result).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "progress.hpp"
#include "results.hpp"

#include "robokin/postures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace robokin::bind {
namespace {

// continuous: (n,) flags, one per joint.
std::vector<bool> flags_arg(ArrayLike continuous, long n) {
  const py::array_t<bool, py::array::c_style | py::array::forcecast> cont = aligned_array<bool>(continuous);
  if (!cont || cont.ndim() != 1 || cont.shape(0) != n)
    fail("continuous: expected a (" + std::to_string(n) + ",) array of booleans");
  return std::vector<bool>(cont.data(), cont.data() + n);
}

// The reconfiguration rule's arguments (qdot_max, dt, continuous, q0), checked: ValueError or
// TypeError naming the argument.
struct RuleArgs {
  Eigen::VectorXd qdot_max, q0;
  std::vector<bool> continuous;
  double dt = 0;
  long n() const { return static_cast<long>(qdot_max.size()); }
  const double* start() const { return q0.size() ? q0.data() : nullptr; }  // q0 given: n values
};

RuleArgs rule_args(ArrayLike qdot_max, double dt, ArrayLike continuous, py::handle q0) {
  RuleArgs a;
  a.qdot_max = as_vector(qdot_max, "qdot_max");
  const long n = a.n();
  if (n < 1 || !(a.qdot_max.array() > 0).all()) fail("qdot_max: expected a positive (n,) array, n >= 1");
  if (!(dt > 0 && std::isfinite(dt))) fail("dt: expected a positive finite number");
  a.dt = dt;
  a.continuous = flags_arg(continuous, n);
  if (!q0.is_none()) a.q0 = as_vector(q0, "q0", n);
  return a;
}

// The programme's arguments: the rule's, the limits and the solution sets, every one checked
// before it runs.
struct PlanArgs {
  RuleArgs rule;
  std::vector<Array> sets;  // kept alive while the GIL is released
  std::vector<PostureLayer> layers;
  JointLimits limits;
};

PlanArgs plan_args(py::handle sets, ArrayLike qdot_max, double dt, ArrayLike continuous, py::handle q0,
                   py::handle limits) {
  PlanArgs a{rule_args(qdot_max, dt, continuous, q0)};
  const long n = a.rule.n();
  a.limits = limits_arg(limits, static_cast<int>(n));
  if (!py::isinstance<py::sequence>(sets) || py::isinstance<py::str>(sets))
    throw py::type_error("sets: expected a sequence of (m, n) arrays");
  for (py::handle s : py::reinterpret_borrow<py::sequence>(sets)) {
    const std::string name = "sets[" + std::to_string(a.sets.size()) + "]";
    Array q = as_array(s, name.c_str());
    if (q.ndim() != 2 || q.shape(1) != n)
      fail(name + ": expected an (m, " + std::to_string(n) + ") array, got " + shape_of(q));
    require_finite(q.data(), q.size(), name.c_str());
    a.sets.push_back(q);
  }
  for (const Array& q : a.sets) a.layers.push_back({q.data(), static_cast<long>(q.shape(0))});
  return a;
}

// (K,) int64: count_reconfigurations of the (K, n) joint path q.
py::array_t<std::int64_t> reconfigurations(ArrayLike q_obj, ArrayLike qdot_max, double dt, ArrayLike continuous,
                                           py::object q0) {
  const RuleArgs a = rule_args(qdot_max, dt, continuous, q0);
  const Array q = rows_arg(q_obj, "q", {a.n()});
  const std::vector<std::int64_t> k = count_reconfigurations(q.data(), static_cast<long>(q.shape(0)), a.n(),
                                                             a.qdot_max.data(), a.dt, a.continuous, a.start());
  return array_of(k.data(), {static_cast<py::ssize_t>(k.size())});
}

// distinct_rows of each waypoint of q (K, S, n) among the rows found (K, S): a list of K (m, n) arrays.
py::list distinct_solutions(ArrayLike q_obj, ArrayLike found_obj, ArrayLike continuous) {
  const Array q = as_array(q_obj, "q");
  if (q.ndim() != 3) fail("q: expected a (K, S, n) array, got " + shape_of(q));
  const long K = q.shape(0), S = q.shape(1), n = q.shape(2);
  const auto found = aligned_array<bool>(found_obj);
  if (!found || found.ndim() != 2 || found.shape(0) != K || found.shape(1) != S)
    fail("found: expected a (K, S) array of booleans for q's (K, S, n)");
  const std::vector<bool> cont = flags_arg(continuous, n);
  py::list sets;
  std::unique_ptr<bool[]> keep(new bool[S]);
  for (long k = 0; k < K; ++k) {
    const double* rows = q.data() + k * S * n;
    std::copy(found.data() + k * S, found.data() + (k + 1) * S, keep.get());
    distinct_rows(rows, S, n, cont, keep.get());
    const long m = std::count(keep.get(), keep.get() + S, true);
    py::array_t<double> set = new_array({m, n});
    double* out = set.mutable_data();
    for (long r = 0; r < S; ++r)
      if (keep[r]) out = std::copy(rows + r * n, rows + (r + 1) * n, out);
    sets.append(set);
  }
  return sets;
}

}  // namespace

void bind_postures(py::module_& m) {
  ResultClass<PosturePlan>(m, "PosturePlan", "track_postures' plan (robokin.track_postures builds its result from it).",
                           false)
      .fields()
      .done();
  m.def(
      "track_postures",
      [](py::object sets, ArrayLike qdot_max, double dt, ArrayLike continuous, py::object q0, LimitsLike limits) {
        const PlanArgs a = plan_args(sets, qdot_max, dt, continuous, q0, limits);
        const RuleArgs& r = a.rule;
        return released([&] {
          return track_postures(a.layers, r.n(), r.qdot_max.data(), r.dt, r.continuous, r.start(), a.limits);
        });
      },
      py::arg("sets"), py::arg("qdot_max"), py::arg("dt"), py::arg("continuous"), py::arg("q0") = py::none(),
      py::arg("limits") = py::none(),
      "track_postures' dynamic programme -> PosturePlan: pick[k] the row of sets[k] chosen (-1 where it\n"
      "is empty) minimising the reconfigurations (a joint moving more than qdot_max * dt per waypoint\n"
      "interval), then the motion (the sum of the steps' norms); ties to the lowest row. q0 (n,) or\n"
      "None: the joints before the path; limits (lower, upper) or None: where continuous joints may be\n"
      "shifted by whole turns along the path. The GIL is released while it runs.");
  m.def("count_reconfigurations", &reconfigurations, py::arg("q"), py::arg("qdot_max"), py::arg("dt"),
        py::arg("continuous"), py::arg("q0") = py::none(),
        "The waypoints of the (K, n) joint path q entered by a reconfiguration, track_postures' rule\n"
        "(int64, in order). Use robokin.count_reconfigurations.");
  m.def("distinct_solutions", &distinct_solutions, py::arg("q"), py::arg("found"), py::arg("continuous"),
        "Each waypoint's solutions q (K, S, n) found (K, S) less their copies (within 1e-6 on every\n"
        "joint of a row kept before): K (m, n) arrays. Use robokin.track_postures(method='numerical').");
}

}  // namespace robokin::bind
