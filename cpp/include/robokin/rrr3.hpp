// The planar 3-RRR parallel robot of the 3-RRR project: inverse and forward models, the seed's Jacobians
// A and B, singularities.
//
// Geometry (DESIGN.md): base joints O_i = R_b u(t_i), platform joints B_i = E + R_e R(phi) u(t_i),
// t_i = -90 deg + 120 deg i, u(a) = (cos a, sin a). Leg i is O_i -(l1)- A_i -(l2)- B_i with
// A_i = O_i + l1 u(alpha_i) and beta_i the elbow angle from link 1 to link 2. A working mode is
// (m_0, m_1, m_2), m_i = sign(beta_i) = +-1. A pose is (x_E, y_E, phi).
#pragma once

#include "robokin/progress.hpp"

#include <Eigen/Dense>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace robokin {

using Pose = Eigen::Vector3d;  // (x, y, phi)
using Mode = std::array<int, 3>;
constexpr Mode kDefaultMode{1, 1, 1};  // the working mode of every call that is not given one

// The seed's robot (R_b, R_e, l1, l2 in metres), the default of every RRR3.
constexpr double kDefaultBaseRadius = 0.13, kDefaultPlatformRadius = 0.07, kDefaultL1 = 0.12, kDefaultL2 = 0.12;
// The seed's singularity tolerance, on the normalised determinants (det A / R_e, det B / l1^3).
constexpr double kSingularTol = 1e-3;
// The distance to parallel singularities (RRR3::distance) that planning keeps: RRR3PlanOptions::margin,
// RRR3ConnectOptions::clearance, and the simulator's "near".
constexpr double kNearDistance = 0.05;
// The smallest |det B| / l1^3 planning allows (never near a serial singularity).
constexpr double kSerialMargin = 0.02;
// Newton's defaults (ik_newton, fk): at most kNewtonMaxIter steps, to a residual below kNewtonTol
// (m). max_iter is accepted in [0, kMaxNewtonIterations]: a run that has not converged in 1e5 steps
// will not, and a larger bound only makes an unreachable target hang.
constexpr int kNewtonMaxIter = 50, kMaxNewtonIterations = 100000;
constexpr double kNewtonTol = 1e-12;

// The options of a Newton run on the loop equations (RRR3::ik_newton, RRR3::fk).
struct RRR3NewtonOptions {
  int max_iter = kNewtonMaxIter;  // Newton steps at most, in [0, kMaxNewtonIterations]
  double tol = kNewtonTol;        // converged when the largest residual (m) is below tol

  // Every option, its Python keyword and its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("max_iter", &RRR3NewtonOptions::max_iter, "Newton steps at most, in [0, 100000].");
    field("tol", &RRR3NewtonOptions::tol, "Converged when the largest loop-closure residual (m) is below tol.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
};

// Throws std::invalid_argument unless every m_i is +1 or -1.
inline void check_mode(const Mode& mode) {
  for (int m : mode)
    if (m != 1 && m != -1) throw std::invalid_argument("mode: every entry must be +1 or -1, got " + std::to_string(m));
}

// A pose a leg cannot reach (|O_i B_i| outside [|l1 - l2|, l1 + l2]).
class LegUnreachable : public std::domain_error {
 public:
  LegUnreachable(int leg, const std::string& what) : std::domain_error(what), leg_(leg) {}
  int leg() const { return leg_; }

 private:
  int leg_;
};

struct RRR3Newton {  // ik_newton's answer
  Eigen::Vector3d alpha, beta;
  bool converged = false;
  int iterations = 0;
  double error = 0;  // largest |O_i + l1 u(a) + l2 u(a + b) - B_i|

  // The fields Python reads, with their docs, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("alpha", &RRR3Newton::alpha, "Actuated angles (3,) (rad).");
    field("beta", &RRR3Newton::beta, "Elbow angles (3,) (rad), link 1 to link 2.");
    field("converged", &RRR3Newton::converged, "The residual fell below tol.");
    field("iterations", &RRR3Newton::iterations, "Newton steps taken.");
    field("error", &RRR3Newton::error, "Largest loop-closure residual (m).");
  }
};

struct RRR3Fk {  // fk's answer
  Pose pose;
  bool converged = false;
  int iterations = 0;
  double error = 0;

  template <class Visit>
  static void fields(Visit&& field) {
    field("pose", &RRR3Fk::pose, "The pose (x, y, phi) found.");
    field("converged", &RRR3Fk::converged, "The residual fell below tol.");
    field("iterations", &RRR3Fk::iterations, "Newton steps taken.");
    field("error", &RRR3Fk::error, "Largest | |A_i B_i| - l2 | (m).");
  }
};

// The seed's singularity classification. Determinants are also given normalised so that one
// tolerance means the same for any robot size: det_a_norm = det A / R_e (A's third column is a
// length; R_e is the platform's size), det_b_norm = det B / l1^3 (e_i = l1 sin(beta_i), so
// det_b_norm = prod sin(beta_i) up to sign).
struct RRR3Singularity {
  std::string kind = "none";  // "none" | "parallel" | "serial"
  double det_a = 0, det_b = 0, det_a_norm = 0, det_b_norm = 0;
  double distance = 0;  // in [0, 1]
  int leg = -1;         // the stretched or folded leg of a serial singularity; -1: none
  std::string lines;    // parallel singularity: "parallel" or "concurrent" lines A_i B_i; "": none

  // The fields Python reads as they are, with their docs, in order (leg and lines, None when
  // there is none, are bound after them).
  template <class Visit>
  static void fields(Visit&& field) {
    field("kind", &RRR3Singularity::kind, "'none', 'parallel' or 'serial'.");
    field("det_a", &RRR3Singularity::det_a, "det A.");
    field("det_b", &RRR3Singularity::det_b, "det B.");
    field("det_a_norm", &RRR3Singularity::det_a_norm, "det A / platform_radius.");
    field("det_b_norm", &RRR3Singularity::det_b_norm, "det B / l1^3.");
    field("distance", &RRR3Singularity::distance,
          "Inverse condition number of A (third column / platform_radius): 0 at a parallel singularity.");
  }
};

class RRR3 {
 public:
  // Throws std::invalid_argument naming the length when one is not in [1e-6, 1e6] m.
  RRR3(double base_radius, double platform_radius, double l1, double l2);

  double base_radius() const { return rb_; }
  double platform_radius() const { return re_; }
  double l1() const { return l1_; }
  double l2() const { return l2_; }

  // The 8 working modes in the order of ik_all's rows: (+,+,+), (+,+,-), (+,-,+), (+,-,-),
  // (-,+,+), ... (itertools.product((1, -1), repeat=3)); mode k has m_i = -1 where bit (2 - i) of k is set.
  static Mode mode_at(int k);

  Eigen::Vector2d base_joint(int i) const { return o_[i]; }
  Eigen::Vector2d platform_joint(const Pose& pose, int i) const;  // B_i in the base frame

  // Analytic inverse model. Writes alpha (3,), wrapped to (-pi, pi]; returns -1 when every leg
  // reaches, else the first leg that cannot (alpha is then NaN from that leg on).
  int ik(const Pose& pose, const Mode& mode, double* alpha) const;
  // ik that throws LegUnreachable naming the leg.
  Eigen::Vector3d ik_or_throw(const Pose& pose, const Mode& mode) const;
  // count poses (count x 3, row-major) -> alpha rows, NaN rows where a leg cannot reach. Uses
  // every core; call without the GIL.
  void ik_batch(const double* poses, long count, const Mode& mode, double* out, Progress* progress = nullptr) const;

  // The seed's numerical inverse model: Newton-Raphson on the 6 loop-closure equations
  // O_i + l1 u(alpha_i) + l2 u(alpha_i + beta_i) - B_i = 0 in (alpha_i, beta_i) from guess.
  RRR3Newton ik_newton(const Pose& pose, const Eigen::Vector3d& alpha0, const Eigen::Vector3d& beta0,
                       const RRR3NewtonOptions& options = {}) const;

  // Forward model by Newton on |A_i B_i|^2 = l2^2 in (x, y, phi) from a guess pose.
  RRR3Fk fk(const Eigen::Vector3d& alpha, const Pose& guess, const RRR3NewtonOptions& options = {}) const;
  // Largest | |A_i B_i| - l2 | of the actuated angles alpha at pose: how far pose is from closing the loops.
  double closure_error(const Eigen::Vector3d& alpha, const Pose& pose) const;
  // Every assembly mode of alpha (at most 6), sorted by phi in [-pi, pi). Each closes the loops
  // to 1e-10 m (1e-10 of R_b + R_e + l1 + l2 when that exceeds 1 m) and is given once, a double
  // root (det A = 0) too; modes closer than the loops can tell in floating point (some 1e-7 of the
  // size near a parallel singularity) are given as one. Where the elbows form a triangle congruent
  // to the platform's, the platform also moves on a continuum (phi fixed, E on a circle of radius
  // l2, the legs parallel; e.g. any equal alpha_i when R_b == R_e): those poses are not returned,
  // only the isolated modes. See rrr3_fk.cpp for the method.
  std::vector<Pose> fk_all(const Eigen::Vector3d& alpha) const;

  // Elbows A_i for the actuated angles (a 3 x 2 matrix, one row per leg).
  Eigen::Matrix<double, 3, 2> elbows(const Eigen::Vector3d& alpha) const;

  // The seed's A (rows [cos g_i, sin g_i, d_i]) and B = diag(e_i) with A v = B alpha_dot, v
  // (v_x, v_y, w) in the effector frame. Throws LegUnreachable.
  void jacobians(const Pose& pose, const Mode& mode, Eigen::Matrix3d& A, Eigen::Matrix3d& B) const;
  // A and B from the pose and the elbows (no inverse model).
  void jacobians_at(const Pose& pose, const Eigen::Matrix<double, 3, 2>& elbows, Eigen::Matrix3d& A,
                    Eigen::Matrix3d& B) const;

  // Classification with tolerance tol on the normalised determinants. Throws LegUnreachable.
  RRR3Singularity singularity(const Pose& pose, const Mode& mode, double tol) const;
  // The inverse condition number of A with its third column divided by R_e (0 at a parallel singularity).
  double distance(const Eigen::Matrix3d& A) const;

 private:
  // fk's loop equations at pose x for the elbows A: f_i = (|A_i B_i|^2 - l2^2) / (2 l2) and their
  // Jacobian in (x, y, phi). Returns max_i | |A_i B_i| - l2 |.
  double loops(const Eigen::Matrix<double, 3, 2>& A, const Pose& x, Eigen::Vector3d& f, Eigen::Matrix3d& J) const;
  // fk for the elbows A of alpha (fk_all polishes each of its roots from the same elbows).
  RRR3Fk close_loops(const Eigen::Matrix<double, 3, 2>& A, const Pose& guess, const RRR3NewtonOptions& options) const;
  // fk_all: poses p and q, closing the loops of A to ep and eq, are one assembly mode.
  bool same_mode(const Eigen::Matrix<double, 3, 2>& A, const Pose& p, double ep, const Pose& q, double eq) const;

  double rb_, re_, l1_, l2_;
  std::array<Eigen::Vector2d, 3> o_;  // base joints O_i
  std::array<Eigen::Vector2d, 3> b_;  // platform joints in the effector frame, R_e u(t_i)
};

}  // namespace robokin
