// General 3R positioning arms: the arm read from a chain and every inverse solution of a point (at
// most 4). Their aspects and cuspidality: cuspidal.hpp.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/ik_closed.hpp"

namespace robokin {

// A 3-joint revolute chain read as base * Rz(s1 q1) * F1 * Rz(s2 q2) * F2 * Rz(s3 q3) * tool, the
// tool point t = tool's origin. Every joint must turn about the z axis of its frame (DH chains).
struct Arm3R {
  Rigid base, F1, F2;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double scale[3] = {1, 1, 1};
  double size = 0;  // sum of the lengths: the tolerance's unit
};

// Throws std::invalid_argument naming what differs.
Arm3R arm_3r(const Chain& chain);

// Every solution (at most 4; more only for the degenerate arms with a continuum, where one is
// returned and `singular` set) putting the tool point at p, from a degree-2 trigonometric
// polynomial in q3 (a quartic in z = exp(i q3), solved as the eigenvalues of its companion
// matrix), or from a degree-1 one when the first two axes are parallel or intersect. Each is
// polished by Newton's method on the forward model and returned only when chain.fk puts the tool
// within 1e-9 x the arm's size of p. Labels: "det J > 0" / "det J < 0" (the aspect's sign), or
// "singular" where |det J| is ~0.
ClosedFormSolutions ik_general_3r(const Arm3R& arm, const Chain& chain, const Eigen::Vector3d& p,
                                  const JointLimits& limits);

// det of the 3 x 3 position Jacobian at (q2, q3) (it does not depend on q1).
double det_3r(const Arm3R& arm, double q2, double q3);

}  // namespace robokin
