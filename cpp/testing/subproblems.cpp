// robokin._testing's hooks of the Paden-Kahan subproblems (subproblems.hpp), for their tests: each
// returns (angles, singular) with the angles as a list; and closed_solve on them alone, for the
// test that the layouts' own closed forms (ik_ur, ik_spherical) give its solutions and labels.
#include "subproblems_hooks.hpp"

#include "arrays.hpp"
#include "robokin/closed_solve.hpp"
#include "robokin/ik_closed.hpp"
#include "robokin/subproblems.hpp"

#include <pybind11/stl.h>

namespace robokin::bind {
namespace {

Eigen::Vector3d v3(ArrayLike obj, const char* name) {
  const Eigen::VectorXd v = as_vector(obj, name, 3);
  return {v(0), v(1), v(2)};
}

py::tuple angles(const SubproblemAngles& t) {
  py::list out;
  for (int i = 0; i < t.count; ++i) out.append(t.turn[i].angle());
  return py::make_tuple(out, t.singular);
}

}  // namespace

void bind_subproblem_hooks(py::module_& m) {
  m.def("subproblem1", [](ArrayLike k, ArrayLike p, ArrayLike q) {
    return angles(subproblem1(v3(k, "k").normalized(), v3(p, "p"), v3(q, "q")));
  }, py::arg("k"), py::arg("p"), py::arg("q"));
  m.def("subproblem2", [](ArrayLike k1, ArrayLike k2, ArrayLike p, ArrayLike q) {
    SubproblemAngles t1, t2;
    subproblem2(v3(k1, "k1").normalized(), v3(k2, "k2").normalized(), v3(p, "p"), v3(q, "q"), t1, t2);
    return py::make_tuple(angles(t1), angles(t2));
  }, py::arg("k1"), py::arg("k2"), py::arg("p"), py::arg("q"));
  m.def("subproblem3", [](ArrayLike k, ArrayLike p, ArrayLike q, double d) {
    return angles(subproblem3(v3(k, "k").normalized(), v3(p, "p"), v3(q, "q"), d));
  }, py::arg("k"), py::arg("p"), py::arg("q"), py::arg("d"));
  m.def("subproblem4", [](ArrayLike h, ArrayLike k, ArrayLike p, double d) {
    return angles(subproblem4(v3(h, "h"), v3(k, "k").normalized(), v3(p, "p"), d));
  }, py::arg("h"), py::arg("k"), py::arg("p"), py::arg("d"));
  // Every solution of the chain's 6R for the tool frame, without limits, by the subproblems whatever
  // the arm's layout -> IKSolutions.
  m.def("closed_solve_subproblems", [](const Chain& chain, ArrayLike target) {
    const ClosedArm arm = closed_arm(chain);
    return closed_solve(arm, chain, Rigid::from_matrix(as_transform(target, "target")), JointLimits{});
  }, py::arg("chain"), py::arg("target"));
  // Which layout's own closed form ClosedSolver takes for the chain: "ur", "spherical" or None.
  m.def("closed_layout", [](const Chain& chain) -> py::object {
    if (chain.closed_layout().ur) return py::str("ur");
    if (chain.closed_layout().spherical) return py::str("spherical");
    return py::none();
  }, py::arg("chain"));
}

}  // namespace robokin::bind
