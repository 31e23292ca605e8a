// General 3R arms: inverse solutions of a point, aspects and cuspidality (use robokin.closed.general_3r
// and robokin.cuspidal).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_args.hpp"
#include "progress.hpp"

#include "robokin/ik_3r.hpp"

#include <cmath>

namespace robokin::bind {

void bind_ik_3r(py::module_& m) {
  m.def(
      "ik_3r",
      [](ArrayLike target, const Chain& chain, ChainLimitsLike limits) {
        const Eigen::VectorXd p = as_vector(target, "target", 3);
        const Arm3R arm = arm_3r(chain);
        JointLimits given;
        return ik_3r(arm, chain, Eigen::Vector3d(p(0), p(1), p(2)), limits_or_default(chain, limits, 3, given));
      },
      py::arg("target"), py::arg("chain"), py::arg("limits"));  // robokin.closed.general_3r holds the default
  m.def(
      "det_3r",
      [](const Chain& chain, double q2, double q3) {
        if (!std::isfinite(q2) || !std::isfinite(q3)) fail("q: must be finite");
        return det_3r(arm_3r(chain), q2, q3);
      },
      py::arg("chain"), py::arg("q2"), py::arg("q3"));
  m.def(
      "cuspidal_3r",
      [](const Chain& chain, int resolution) {
        if (resolution < 16 || resolution > 4096) fail("resolution: expected an integer in [16, 4096]");
        const Arm3R arm = arm_3r(chain);
        const CuspidalResult r = released([&] { return cuspidal_3r(arm, resolution); });
        py::array_t<double> cusps = new_array({static_cast<py::ssize_t>(r.cusps.size()), 4});
        double* c = cusps.mutable_data();
        for (size_t k = 0; k < r.cusps.size(); ++k) {
          c[4 * k] = r.cusps[k].q2, c[4 * k + 1] = r.cusps[k].q3, c[4 * k + 2] = r.cusps[k].rho, c[4 * k + 3] = r.cusps[k].z;
        }
        py::dict out;
        out["label"] = array_of(r.label.data(), {resolution, resolution});
        out["cuspidal"] = r.cuspidal;
        out["cusps"] = cusps;
        out["aspects"] = r.aspects;
        out["sign"] = array_of(r.sign.data(), {resolution, resolution});
        out["grid"] = array_of(r.grid.data(), {resolution});
        return out;
      },
      py::arg("chain"), py::arg("resolution"));
}

}  // namespace robokin::bind
