// Seed 000's planar RPR arm: its closed-form self-motion set.
#include "arrays.hpp"
#include "bindings.hpp"

#include "robokin/rpr.hpp"

namespace robokin::bind {

void bind_rpr(py::module_& m) {
  m.def(
      "rpr_self_motion",
      [](ArrayLike point, ArrayLike t1_obj, double l1, double l3, ArrayLike lower_obj, ArrayLike upper_obj) {
        const Eigen::VectorXd p = as_vector(point, "point", 2);
        const Eigen::VectorXd t1 = as_vector(t1_obj, "t1");
        const Eigen::VectorXd lower = as_vector(lower_obj, "lower", 3, false);
        const Eigen::VectorXd upper = as_vector(upper_obj, "upper", 3, false);
        if (!(std::isfinite(l1) && l1 > 0)) fail("l1: must be a positive finite length");
        if (!(std::isfinite(l3) && l3 > 0)) fail("l3: must be a positive finite length");
        if (lower.hasNaN() || upper.hasNaN() || (lower.array() > upper.array()).any())
          fail("limits: lower must be <= upper, without NaN");
        const auto count = static_cast<py::ssize_t>(t1.size());
        py::array_t<double> out = new_array({2, count, 3});
        rpr_self_motion(p.head<2>(), t1.data(), count, l1, l3, lower, upper, out.mutable_data());
        return out;
      },
      py::arg("point"), py::arg("t1"), py::arg("l1"), py::arg("l3"), py::arg("lower"), py::arg("upper"),
      "Self-motion set of the RPR tip point: (2, K, 3) joints per t1 sample and branch, NaN where none.");
}

}  // namespace robokin::bind
