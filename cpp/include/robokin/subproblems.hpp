// The Paden-Kahan subproblems: rotations about unit axes through the origin (points are taken
// relative to a point on the axis by the caller). R(k, theta) is the right-handed rotation by theta
// about the unit vector k. Subproblems 2 to 4 return their exact solutions only (none when the data
// admit none, beyond a relative rounding margin of kSubproblemEps); each flags a continuum (every
// angle a solution: 0 is returned) or two solutions that coincide.
#pragma once

#include <Eigen/Core>

namespace robokin {

// Relative margin within which a cosine beyond 1 is taken as 1 (two coinciding solutions) and two
// norms or projections are taken as equal.
constexpr double kSubproblemEps = 1e-12;

// Up to two angles of one subproblem.
struct SubproblemAngles {
  int count = 0;
  double theta[2] = {0, 0};
  // A continuum (theta[0] = 0 chosen), or two solutions within the margin of coinciding (count 1
  // when they are equal, else both, ~1e-6 apart at most).
  bool singular = false;
};

// R(k, theta) as a matrix (Rodrigues' formula).
Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& k, double theta);

// Subproblem 1: theta with R(k, theta) p = q when |p| = |q| and k.p = k.q; otherwise the angle that
// brings R p nearest to q (the callers pass data consistent by construction, up to rounding, and
// check the result). A continuum when p is on the axis.
SubproblemAngles subproblem1(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q);

// Subproblem 2: (theta1, theta2) with R(k1, theta1) R(k2, theta2) p = q, k1 and k2 not parallel:
// up to two pairs, theta1 in t1.theta[i] with theta2 in t2.theta[i].
void subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2);

// Subproblem 3: theta with |R(k, theta) p - q| = d (d >= 0).
SubproblemAngles subproblem3(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d);

// Subproblem 4: theta with h . R(k, theta) p = d.
SubproblemAngles subproblem4(const Eigen::Vector3d& h, const Eigen::Vector3d& k, const Eigen::Vector3d& p, double d);

}  // namespace robokin
