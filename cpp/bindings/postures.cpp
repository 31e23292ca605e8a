// The dynamic programme of robokin.track_postures (use robokin.track_postures, which finds the
// solution sets and builds the result).
#include "arrays.hpp"
#include "bindings.hpp"
#include "progress.hpp"

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
  bool has_q0 = false;
  double dt = 0;
};

PlanArgs plan_args(py::handle sets, ArrayLike qdot_max, double dt, ArrayLike continuous, py::handle q0) {
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
  m.def(
      "track_postures",
      [](py::object sets, ArrayLike qdot_max, double dt, ArrayLike continuous, py::object q0) {
        const PlanArgs a = plan_args(sets, qdot_max, dt, continuous, q0);
        const PosturePlan plan = released([&] {
          return track_postures(a.layers, static_cast<long>(a.qdot_max.size()), a.qdot_max.data(), a.dt, a.continuous,
                                a.has_q0 ? a.q0.data() : nullptr);
        });
        const py::array_t<long> pick = array_of(plan.pick.data(), {static_cast<py::ssize_t>(plan.pick.size())});
        const py::array_t<long> reconfigured =
            array_of(plan.reconfigured.data(), {static_cast<py::ssize_t>(plan.reconfigured.size())});
        return py::make_tuple(pick, reconfigured, plan.motion);
      },
      py::arg("sets"), py::arg("qdot_max"), py::arg("dt"), py::arg("continuous"), py::arg("q0") = py::none(),
      "track_postures' dynamic programme: (pick, reconfigured, motion), pick[k] the row of sets[k]\n"
      "chosen (-1 where it is empty) minimising the reconfigurations (a joint moving more than\n"
      "qdot_max * dt per waypoint interval), then the motion (the sum of the steps' norms); ties to the\n"
      "lowest row. reconfigured: the waypoints the chosen rows enter by a reconfiguration. q0 (n,) is\n"
      "the joints before the path. The GIL is released while it runs.");
}

}  // namespace robokin::bind
