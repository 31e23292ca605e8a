// General 3R arms: every inverse solution of a point (use robokin.closed.general_3r).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"

#include "robokin/general_3r.hpp"

namespace robokin::bind {

void bind_general_3r(py::module_& m) {
  m.def(
      "ik_general_3r",
      [](ArrayLike target, const Chain& chain, ChainLimitsLike limits) {
        const Eigen::VectorXd p = as_vector(target, "target", 3);
        const Arm3R arm = arm_3r(chain);
        JointLimits given;
        return ik_general_3r(arm, chain, Eigen::Vector3d(p(0), p(1), p(2)), limits_or_default(chain, limits, 3, given));
      },
      py::arg("target"), py::arg("chain"), py::arg("limits"));  // robokin.closed.general_3r holds the default
}

}  // namespace robokin::bind
