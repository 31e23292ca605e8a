// Closed-form inverse kinematics (the IK course): every solution of a pose, each labelled by its
// posture and marked within the joint limits or not (none is dropped for its limits: a solution is
// shifted by 2 pi into them where that fits, and marked outside otherwise). An empty set (never an
// exception) when out of reach; std::invalid_argument naming a length that is not finite (a1, a2,
// a2 of an arm: not positive).
#pragma once

#include "robokin/chain.hpp"
#include "robokin/limits.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace robokin {

// |c| beyond 1 by more than this: out of reach; within it of 1: the singular (coinciding) case.
constexpr double kClosedCosEps = 1e-12;
// Every solution is checked against the forward model before it is returned: the closed forms
// clamp cosines within kClosedCosEps of +-1 and fix a free joint at a singularity, so a pose a hair
// out of reach, or lost to rounding, must not pass as a solution. Position error at most
// kClosedTolP times the arm's size (the sum of its lengths), orientation error (any rotation-matrix
// entry) at most kClosedTolR.
constexpr double kClosedTolP = 1e-9, kClosedTolR = 1e-8;

// That check: the frame F reaches the target T, for an arm of `size` (the distance compared in
// squares: no square root's latency before the verdict). The squared tolerance is capped at the
// largest float: for an arm so large that it overflows, an infinite squared distance still fails
// (the cap refuses some answers of such an arm, never passes a wrong one).
inline bool closed_reaches(const Rigid& F, const Rigid& T, double size) {
  const double tol = kClosedTolP * size;
  return (F.p - T.p).squaredNorm() <= std::min(tol * tol, std::numeric_limits<double>::max()) &&
         (F.R - T.R).cwiseAbs().maxCoeff() <= kClosedTolR;
}

// Throws std::invalid_argument("name: must be finite" or "name: must be positive") for a length
// of a closed form's arm that is not.
void check_length(double value, const char* name, bool positive = false);

// A set of solutions: row k of q is one joint vector, postures[k] its label, within_limits[k]
// whether it is within the joint limits (fit_limits, limits.hpp: true for every row without
// limits). Held inline (no allocation: a closed form returns at most kMaxSolutions of at most
// kMaxDof joints).
struct ClosedFormSolutions {
  static constexpr int kMaxSolutions = 8, kMaxDof = 7;  // 7: a 6R's closed form with a seventh joint held
  int dof = 0;
  std::array<double, kMaxSolutions * kMaxDof> q{};  // row-major: the first count() rows of dof values
  std::array<const char*, kMaxSolutions> postures{};  // static strings: no allocation per label
  std::array<bool, kMaxSolutions> within_limits{};
  bool singular = false;  // the pose is at a singularity (coinciding or infinitely many solutions)

  int count() const { return n_; }
  const double* row(int k) const { return q.data() + k * dof; }
  double* row(int k) { return q.data() + k * dof; }
  // Appends a solution; throws std::length_error beyond kMaxSolutions rows or kMaxDof joints.
  void add(const double* joints, const char* posture, bool within = true) {
    if (n_ >= kMaxSolutions || dof < 1 || dof > kMaxDof) throw std::length_error("ClosedFormSolutions: at most 8 solutions of 1 to 7 joints");
    std::copy(joints, joints + dof, row(n_));
    within_limits[n_] = within;
    postures[n_++] = posture;
  }

 private:
  int n_ = 0;
};

// Planar RP (the IK course, example 1): tip d2 (cos theta1, sin theta1). Solutions (theta1, d2): the
// stroke forward (d2 >= 0) and, when the limits allow a negative stroke, the one backwards.
// At the origin theta1 is free: one solution theta1 = 0, d2 = 0, flagged singular.
ClosedFormSolutions ik_planar_rp(double px, double py, const JointLimits& limits);

// Planar 2R with links a1, a2: tip position (px, py). Elbow down (theta2 in (0, pi)) and elbow up.
ClosedFormSolutions ik_planar_2r(double a1, double a2, double px, double py, const JointLimits& limits);

// Planar 3R with links a1..a3 and tool orientation phi (the IK course, example 2), by the algebraic
// method (c2, s2 = +-sqrt(1 - c2^2), s1, c1) or the geometric one (law of cosines, alpha +- beta).
// When s2 = 0 the two postures coincide: one solution, flagged singular.
ClosedFormSolutions ik_planar_3r(double a1, double a2, double a3, double px, double py, double phi,
                                 bool geometric, const JointLimits& limits);

// The arm of a 6R robot with a spherical wrist, standard DH: (a1, pi/2, d1), (a2, 0, 0),
// (a3, -pi/2 or 0, d3), then a wrist whose centre is d4 along z3 (the ortho-parallel layout of most
// industrial arms: a1 = 0 for the PUMA and the ABB IRB 120, 0.26 m for the KUKA KR 16). With
// a1 = d3 = d4 = 0 this is the anthropomorphic arm (0, pi/2, d1), (a2, 0, 0), (a3, 0, 0) of the course.
struct ArmGeometry {
  double d1 = 0, a2 = 0, a3 = 0, d3 = 0, d4 = 0, a1 = 0;

  // Throws std::invalid_argument("name: ...") unless every length is finite, a2 positive and the
  // forearm has a length (a3 or d4 non-zero).
  void validate() const;
  // The arm's size, the scale of the FK check: the sum of its lengths and of d6's.
  double size(double d6 = 0.0) const;
};

// The anthropomorphic arm: tip position p; 4 postures (shoulder right / left x elbow up / down).
ClosedFormSolutions ik_anthropomorphic(const ArmGeometry& arm, const Eigen::Vector3d& p,
                                       const JointLimits& limits);

// A 6R arm with a spherical wrist in the PUMA 560 layout (standard DH):
//   (0, pi/2, d1), (a2, 0, 0), (a3, -pi/2, d3), (0, pi/2, d4), (0, -pi/2, 0), (0, 0, d6)
// For the target tool frame T: up to 8 solutions, shoulder right / left x elbow up / down x wrist
// flip / no flip. When s5 = 0 (wrist singular) q4 + q6 is fixed: q4 is set to 0 (or pi).
ClosedFormSolutions ik_spherical_wrist_6r(const ArmGeometry& arm, double d6, const Rigid& T,
                                          const JointLimits& limits);

// The ortho-parallel spherical-wrist layout read from a chain's geometry, as URArm is for the UR
// layout: the chain's joint i turns the DH angle scale * q + theta, base and tool are the fixed
// frames before joint 1 and after joint 6 (the DH arm's tool offset d6 is 0: the wrist centre is
// frame 6's origin).
struct SphericalArm {
  ArmGeometry arm;
  double theta[6] = {0, 0, 0, 0, 0, 0};
  double scale[6] = {1, 1, 1, 1, 1, 1};
  Rigid base, tool;
  double size = 0;  // the FK check's scale: arm.size() and the base's and tool's offsets
};

// The chain's ortho-parallel geometry read from its joint axes at q = 0, whatever describes it:
// axes 1 and 2 at a right angle (a1 apart), 2 and 3 parallel and apart, 3 and 4 at a right angle,
// 4, 5, 6 meeting in one point at right angles (to 1e-9 rad and 1e-9 of the arm's size). Throws
// std::invalid_argument("robot: not an arm of the spherical-wrist layout (...)") naming what differs.
SphericalArm spherical_arm(const Chain& chain);

// Every solution of the tool frame T (up to 8) in the chain's joints, as ik_spherical_wrist_6r's
// (the same labels, which are closed_solve.hpp's geometric ones), each checked by chain.fk and
// marked within the limits or not; slot[k] (when given, size 8) is row k's slot as kURPostures'.
ClosedFormSolutions ik_spherical(const SphericalArm& arm, const Chain& chain, const Rigid& T,
                                 const JointLimits& limits, int* slot = nullptr);
// ik_spherical on many frames, as ik_ur_batch.
void ik_spherical_batch(const SphericalArm& arm, const Chain& chain, const Rigid* targets, long count,
                        const JointLimits& limits, double* q_out, bool* within_limits, bool* singular,
                        Progress* progress = nullptr);

// Along a path of tool frames: for each, the spherical-wrist solution within the limits nearest to
// the previous joints (q0 for the first), revolute angles shifted by 2 pi towards the previous value
// within the limits and |q| <= 2^20 rad (where a double still holds an angle to 1.2e-10 rad): no
// branch jumps. ok[k] false (row k = previous joints) where the frame has no solution within the
// limits; reachable[k] true where it has one, within the limits or not (ok implies reachable).
void ik_spherical_wrist_6r_path(const ArmGeometry& arm, double d6, const Rigid* targets, long count,
                                const double* q0, const JointLimits& limits, double* q_out, bool* ok,
                                bool* reachable, Progress* progress = nullptr);

// Row of `solutions` nearest to q among those within the limits (Euclidean distance between joint
// vectors); -1 when none is.
int nearest_solution(const ClosedFormSolutions& solutions, const double* q);

// ---------------------------------------------------------------------------------------------
// The Universal Robots family (UR3/5/10/16, e-series): three parallel axes (2, 3, 4), standard DH
//   (0, pi/2, d1), (a2, 0, 0), (a3, 0, 0), (0, pi/2, d4), (0, -pi/2, d5), (0, 0, d6)
// read from a chain's joint axes (ur_arm, below): the chain's joint i turns the DH angle
// scale * q + theta; the fixed frames before joint 1 and after joint 6 are the base and the tool.
struct URArm {
  double d1 = 0, a2 = 0, a3 = 0, d4 = 0, d5 = 0;
  double theta[6] = {0, 0, 0, 0, 0, 0};  // DH angle = scale * q + theta
  double scale[6] = {1, 1, 1, 1, 1, 1};  // +1 or -1
  Rigid base, tool;                      // fixed frames before joint 1 and after joint 6
  double size = 0;                       // the FK check's scale: the lengths' and the offsets' sum
};

// The chain's UR geometry read from its joint axes at q = 0, whatever describes it (DH rows, a
// URDF): axes 1, 2 meeting at a right angle, 2, 3, 4 parallel and apart, 4, 5 and 5, 6 meeting at
// right angles (to 1e-9 rad and 1e-9 of the arm's size). Throws std::invalid_argument("robot: not
// an arm of the UR layout (...)") naming what differs otherwise.
URArm ur_arm(const Chain& chain);

// The chain's layout when it is one with a closed form of its own: ur_arm's reading, else
// spherical_arm's, else neither (the choice ClosedSolver makes). It depends on the geometry alone:
// Chain::closed_layout reads it once per chain.
struct ClosedLayout {
  std::optional<URArm> ur;
  std::optional<SphericalArm> spherical;
};
ClosedLayout read_closed_layout(const Chain& chain);

// Slots of the 8 UR solutions: shoulder (0 left, 1 right) * 4 + elbow (0 up, 1 down) * 2 + wrist
// (0 no flip, 1 flip). "shoulder left": the wrist centre (origin of frame 5) on the -x side of
// frame 1 (x1 horizontal, perpendicular to joint 2's axis); "elbow up": the elbow above the line
// from the shoulder to the origin of frame 4; "wrist no flip": the DH angle of joint 5 in [0, pi].
extern const char* const kURPostures[8];

// Every solution of the tool frame T (up to 8), in joint variables of `chain` (the arm of `arm`),
// each checked by chain.fk and marked within the limits or not. slot[k] (when given, size 8) is row k's
// slot. Singular cases, flagged: at the shoulder (wrist centre at distance |d4| from axis 1) and
// the elbow (q3 = 0 or pi) two postures coincide and one is returned ("shoulder singular", "elbow
// straight" / "elbow folded"); at the wrist (joint 5 at 0 or pi) axes 2, 3, 4 and 6 are parallel,
// a one-parameter continuum of solutions: one representative per shoulder and elbow ("wrist
// singular"), its q2 + q3 + q4 chosen so that the elbow is as far from stretched as it can be.
ClosedFormSolutions ik_ur(const URArm& arm, const Chain& chain, const Rigid& T, const JointLimits& limits,
                          int* slot = nullptr);

// A batch of frames: q_out (count, 8, 6) row-major, solution in its slot, NaN where the slot has
// none (the pose out of reach, or the posture coinciding with another at a singularity);
// within_limits (count, 8), false where the slot has none; singular (count,). Runs on every core
// (parallel_for); callers release the GIL.
void ik_ur_batch(const URArm& arm, const Chain& chain, const Rigid* targets, long count, const JointLimits& limits,
                 double* q_out, bool* within_limits, bool* singular, Progress* progress = nullptr);

}  // namespace robokin
