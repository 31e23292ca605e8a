// The Paden-Kahan subproblems: rotations about unit axes through the origin (points are taken
// relative to a point on the axis by the caller). R(k, theta) is the right-handed rotation by theta
// about the unit vector k. Subproblems 2 to 4 return their exact solutions only (none when the data
// admit none, beyond a relative rounding margin of kSubproblemEps); each flags a continuum (every
// angle a solution: 0 is returned) or two solutions that coincide.
//
// An angle travels as its cosine and sine (Turn): the subproblems find them by algebra, rotations
// are built from them, and the arc tangent is taken once, where an angle is returned (a closed form
// takes those of all its candidates together).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace robokin {

// Relative margin within which a cosine beyond 1 is taken as 1 (two coinciding solutions) and two
// norms or projections are taken as equal.
constexpr double kSubproblemEps = 1e-12;

// An angle as (cos, sin). Sums and differences keep the pair on the unit circle to rounding.
struct Turn {
  double c = 1.0, s = 0.0;
  double angle() const { return std::atan2(s, c); }
  Turn operator-() const { return {c, -s}; }
  friend Turn operator+(const Turn& a, const Turn& b) { return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s}; }
  friend Turn operator-(const Turn& a, const Turn& b) { return a + -b; }
  // The angle times sign (+1 or -1): a turn about an axis pointing against another.
  Turn times(double sign) const { return {c, sign * s}; }
};

// The turn of the direction (x, y): (x, y) / |(x, y)|, the angle 0 when both are 0.
Turn direction(double x, double y);

// Up to two angles of one subproblem.
struct SubproblemAngles {
  int count = 0;
  Turn turn[2];
  // A continuum (the angle 0 chosen), or two solutions within the margin of coinciding (count 1
  // when they are equal, else both, ~1e-6 apart at most).
  bool singular = false;
};

// R(k, theta) as a matrix, c I + s [k]x + (1 - c) k k^T (Rodrigues' formula), and R(k, theta) v.
inline Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& k, const Turn& t) {
  Eigen::Matrix3d R = (1.0 - t.c) * k * k.transpose();
  R.diagonal().array() += t.c;
  const Eigen::Vector3d sk = t.s * k;
  R(0, 1) -= sk.z(), R(1, 0) += sk.z();
  R(0, 2) += sk.y(), R(2, 0) -= sk.y();
  R(1, 2) -= sk.x(), R(2, 1) += sk.x();
  return R;
}

inline Eigen::Vector3d rotate(const Eigen::Vector3d& k, const Turn& t, const Eigen::Vector3d& v) {
  return t.c * v + t.s * k.cross(v) + ((1.0 - t.c) * k.dot(v)) * k;
}

// Subproblem 1: theta with R(k, theta) p = q when |p| = |q| and k.p = k.q; otherwise the angle that
// brings R p nearest to q (the callers pass data consistent by construction, up to rounding, and
// check the result). A continuum when p is on the axis.
SubproblemAngles subproblem1(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q);

// Subproblem 2: (theta1, theta2) with R(k1, theta1) R(k2, theta2) p = q, k1 and k2 not parallel:
// up to two pairs, theta1 in t1.turn[i] with theta2 in t2.turn[i].
void subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2);

// Subproblem 2 for fixed k1, k2 and p and many q (a spherical wrist's axes and tool axis): what
// depends on them alone is taken once.
class Subproblem2 {
 public:
  Subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p);
  void solve(const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2) const;

 private:
  Eigen::Vector3d k1_, k2_, k2xk1_, pp_, w_;  // pp_ p's part normal to k2, w_ = k2 x pp_
  double k2k1_, k2p_, k2sq_, p2_, pp2_;
};

// Subproblem 3: theta with |R(k, theta) p - q| = d (d >= 0).
SubproblemAngles subproblem3(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d);

// Subproblem 4: theta with h . R(k, theta) p = d.
SubproblemAngles subproblem4(const Eigen::Vector3d& h, const Eigen::Vector3d& k, const Eigen::Vector3d& p, double d);

}  // namespace robokin
