// Trajectories with time laws: joint-space quintic polynomials, trapezoidal velocity profiles with
// per-joint velocity and acceleration limits (synchronised), linear segments with parabolic blends
// through via points, and Cartesian straight lines between two poses (position linear, orientation
// by quaternion SLERP) under the quintic or trapezoidal law. Planning is cheap and done once; the
// evaluation at many sample times writes into caller-provided buffers (no allocation, no Python:
// the binding releases the GIL and splits long evaluations over the cores).
#pragma once

#include "robokin/chain.hpp"

#include <Eigen/Dense>

#include <vector>

namespace robokin {

// Output buffers of a joint trajectory sampled at `count` times: q, qd, qdd are count x n, row-major.
struct JointSamples {
  double* q;
  double* qd;
  double* qdd;
};

// A quintic from (q0, qd0) at time t0 to (q1, qd1) at time t1, zero acceleration at both ends.
// Samples at exactly t0 / t1 (and before / after) are the boundary values, exactly.
class Quintic {
 public:
  Quintic(const Vector& q0, const Vector& q1, const Vector& qd0, const Vector& qd1, double t0, double t1);
  int dof() const { return static_cast<int>(q0_.size()); }
  void evaluate(const double* t, long begin, long end, const JointSamples& out) const;

 private:
  Vector q0_, q1_, qd0_, qd1_;
  double t0_, t1_;
  Eigen::Matrix<double, Eigen::Dynamic, 6> c_;  // per joint: q(tau) = sum c_k tau^k, tau = (t - t0) / T
};

// Trapezoidal velocity, synchronised: the slowest joint runs its time-optimal profile (full
// acceleration to its velocity limit, or a triangle when the distance is too short), every other
// joint accelerates at its own limit to the lower cruise velocity that makes it arrive at the same
// time. |qd_i| <= vmax_i and |qdd_i| <= amax_i throughout; the motion starts at t = 0.
class Trapezoid {
 public:
  Trapezoid(const Vector& q0, const Vector& q1, const Vector& vmax, const Vector& amax);
  int dof() const { return static_cast<int>(q0_.size()); }
  double duration() const { return T_; }
  void evaluate(const double* t, long begin, long end, const JointSamples& out) const;

 private:
  Vector q0_, q1_, v_, a_, ta_;  // per joint: cruise speed, acceleration, acceleration time (0 if still)
  double T_ = 0.0;
};

// Straight segments between via points joined by parabolic blends (Craig, "linear function with
// parabolic blends" through via points). Segment j lasts as long as its slowest joint needs at its
// velocity limit; the blend at via k lasts as long as the joint with the largest velocity change
// needs at its acceleration limit; segments too short for their two half blends are lengthened.
// The motion starts at rest exactly at the first point and ends at rest exactly at the last one;
// an inner via point is passed within its blend (exactly when the velocity does not change there).
class ViaPath {
 public:
  // points: M x n (M >= 1); repeated consecutive points are merged.
  ViaPath(const Eigen::MatrixXd& points, const Vector& vmax, const Vector& amax);
  int dof() const { return static_cast<int>(p_.cols()); }
  double duration() const { return T_; }
  // Times at which the straight segments pass the via points (the middle of each blend).
  const Vector& via_times() const { return tau_; }
  void evaluate(const double* t, long begin, long end, const JointSamples& out) const;

 private:
  Eigen::MatrixXd p_, v_;  // via points (M x n); v_ row j: velocity of segment j (M - 1 rows)
  Vector tau_, tb_;        // per via point: time, blend duration
  double T_ = 0.0;
};

// A Cartesian straight line from T0 to T1: the position moves along the segment, the orientation
// by SLERP from R0 to R1 (the shortest rotation, about one fixed axis). The time law moves the
// distance along the segment and the rotation angle: both by one quintic over [t0, t1], or by a
// synchronised trapezoid with (linear, angular) velocity and acceleration limits.
class CartesianLine {
 public:
  CartesianLine(const Rigid& T0, const Rigid& T1);
  double length() const { return length_; }  // |p1 - p0|
  double angle() const { return angle_; }    // rotation angle from R0 to R1, in [0, pi]
  // Poses (count x 16, row-major 4x4), twists and their derivatives (count x 6, rows v_x v_y v_z
  // w_x w_y w_z in the base frame) from the law's samples x (count x 2: distance, angle), xd, xdd.
  void evaluate(const double* x, const double* xd, const double* xdd, long begin, long end, double* poses,
                double* velocity, double* acceleration) const;

 private:
  Rigid T0_, T1_;
  Eigen::Vector3d u_;      // unit direction of the segment (0 when the length is 0)
  Eigen::Vector4d q0_;     // R0 as a quaternion (w, x, y, z)
  Eigen::Vector3d axis_;   // rotation axis in R0's frame (unit)
  Eigen::Vector3d waxis_;  // the same in the base frame
  double length_ = 0.0, angle_ = 0.0;
};

// Sample times 0, dt, 2 dt, ... and `duration` itself (the last sample); one sample when the
// duration is 0. Throws std::invalid_argument (naming dt) when there would be more than max_samples.
std::vector<double> sample_times(double duration, double dt, long max_samples);

}  // namespace robokin
