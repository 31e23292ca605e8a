// General 3R positioning arms: every inverse solution of a point (at most 4), the
// aspects (regions of constant sign of det J) and cuspidality (a cusp point on the singular curves).
#pragma once

#include "robokin/chain.hpp"
#include "robokin/ik_closed.hpp"

#include <vector>

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
ClosedFormSolutions ik_3r(const Arm3R& arm, const Chain& chain, const Eigen::Vector3d& p, const JointLimits& limits);

// det of the 3 x 3 position Jacobian at (q2, q3) (it does not depend on q1).
double det_3r(const Arm3R& arm, double q2, double q3);

struct CuspPoint {
  double q2, q3;   // on the singular curve, in joint variables
  double rho, z;   // the workspace point: distance from axis 1 and height (base frame)
};

struct CuspidalResult {
  bool cuspidal = false;
  std::vector<CuspPoint> cusps;
  int aspects = 0;                 // connected regions of constant sign of det J on the (q2, q3) torus
  std::vector<signed char> sign;   // resolution x resolution grid of sign(det J), row = q2
  std::vector<int> label;          // the aspect of each grid cell (-1 where det J = 0)
  std::vector<double> grid;        // the grid's angles (for q2 and q3), below
  int resolution = 0;
};

// The grid: q = -pi + (i + 0.37) 2 pi / resolution, i = 0 .. resolution - 1 (for q2 and q3).
// Traces det D = 0 (D: the 2 x 2 Jacobian of (q2, q3) -> (rho, z)) on a resolution x resolution
// grid of the torus, and finds where the image of the curve's tangent, D tau, reverses (a cusp of
// the singular curve in the workspace, where three solutions coincide); each is refined by
// bisection along the curve.
CuspidalResult cuspidal_3r(const Arm3R& arm, int resolution);

}  // namespace robokin
