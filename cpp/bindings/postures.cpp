// The dynamic programme of robokin.track_postures (use robokin.track_postures, which finds the
// solution sets and builds the result).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "progress.hpp"
#include "results.hpp"

#include "robokin/postures.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace robokin::bind {
namespace {

// Every argument checked (ValueError or TypeError naming it) before the programme runs.
struct PlanArgs {
  std::vector<Array> sets;  // kept alive while the GIL is released
  std::vector<PostureLayer> layers;
  Eigen::VectorXd qdot_max, q0;
  std::vector<bool> continuous;
  JointLimits limits;
  bool has_q0 = false;
  double dt = 0;
};

PlanArgs plan_args(py::handle sets, ArrayLike qdot_max, double dt, ArrayLike continuous, py::handle q0,
                   py::handle limits) {
  PlanArgs a;
  a.qdot_max = as_vector(qdot_max, "qdot_max");
  const long n = a.qdot_max.size();
  if (n < 1 || !(a.qdot_max.array() > 0).all()) fail("qdot_max: expected a positive (n,) array, n >= 1");
  if (!(dt > 0 && std::isfinite(dt))) fail("dt: expected a positive finite number");
  a.dt = dt;
  const py::array_t<bool, py::array::c_style | py::array::forcecast> cont = aligned_array<bool>(continuous);
  if (!cont || cont.ndim() != 1 || cont.shape(0) != n) fail("continuous: expected a (" + std::to_string(n) + ",) array of booleans");
  a.continuous.assign(cont.data(), cont.data() + n);
  if (!q0.is_none()) a.q0 = as_vector(q0, "q0", n), a.has_q0 = true;
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
        return released([&] {
          return track_postures(a.layers, static_cast<long>(a.qdot_max.size()), a.qdot_max.data(), a.dt, a.continuous,
                                a.has_q0 ? a.q0.data() : nullptr, a.limits);
        });
      },
      py::arg("sets"), py::arg("qdot_max"), py::arg("dt"), py::arg("continuous"), py::arg("q0") = py::none(),
      py::arg("limits") = py::none(),
      "track_postures' dynamic programme -> PosturePlan: pick[k] the row of sets[k] chosen (-1 where it\n"
      "is empty) minimising the reconfigurations (a joint moving more than qdot_max * dt per waypoint\n"
      "interval), then the motion (the sum of the steps' norms); ties to the lowest row. q0 (n,) or\n"
      "None: the joints before the path; limits (lower, upper) or None: where continuous joints may be\n"
      "shifted by whole turns along the path. The GIL is released while it runs.");
}

}  // namespace robokin::bind
