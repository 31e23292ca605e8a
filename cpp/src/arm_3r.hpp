// The kinematics of an Arm3R at the angles t = s q (s: each joint's sign, Arm3R::scale): points,
// derivatives and det J, shared by the general 3R closed form and the cuspidality test.
#pragma once

#include "robokin/general_3r.hpp"

#include <cmath>

namespace robokin::arm_3r_model {

inline Eigen::Matrix3d rz(double a) {
  Eigen::Matrix3d m;
  const double c = std::cos(a), s = std::sin(a);
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

// e_z x v
inline Eigen::Vector3d ez_cross(const Eigen::Vector3d& v) { return {-v.y(), v.x(), 0.0}; }

// Points and derivatives in the frame after joint 1's rotation, at the angles t2, t3.
struct Local {
  Eigen::Vector3d w, u, du2, du3;
};

inline Local local(const Arm3R& a, double t2, double t3) {
  Local L;
  const Eigen::Vector3d r3 = rz(t3) * a.tip;
  L.w = a.F2.R * r3 + a.F2.p;
  const Eigen::Matrix3d R2 = rz(t2);
  const Eigen::Vector3d v = R2 * L.w;
  L.u = a.F1.R * v + a.F1.p;
  L.du2 = a.F1.R * ez_cross(v);
  L.du3 = a.F1.R * (R2 * (a.F2.R * ez_cross(r3)));
  return L;
}

// The tool point in the base frame.
inline Eigen::Vector3d position(const Arm3R& a, const double t[3]) {
  return a.base.R * (rz(t[0]) * local(a, t[1], t[2]).u) + a.base.p;
}

// The 3 x 3 position Jacobian with respect to t.
inline Eigen::Matrix3d jacobian(const Arm3R& a, const double t[3]) {
  const Local L = local(a, t[1], t[2]);
  const Eigen::Matrix3d R = a.base.R * rz(t[0]);
  Eigen::Matrix3d J;
  J.col(0) = R * ez_cross(L.u);
  J.col(1) = R * L.du2;
  J.col(2) = R * L.du3;
  return J;
}

// det J at (0, t2, t3): rho det D up to its sign, smooth everywhere (det D alone is not across
// axis 1).
inline double det_t(const Arm3R& a, double t2, double t3) {
  const double t[3] = {0.0, t2, t3};
  return jacobian(a, t).determinant();
}

}  // namespace robokin::arm_3r_model
