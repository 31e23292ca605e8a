// Closed-form inverse kinematics: the planar arms of the IK course, the PUMA-type 6R arm and the UR family.
#include "robokin/ik_closed.hpp"
#include "robokin/angles.hpp"
#include "robokin/parallel.hpp"

#include "closed_batch.hpp"
#include "posture_label.hpp"

#include "kernel/fast_math.hpp"


#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace robokin {
namespace {

constexpr double kCosEps = kClosedCosEps;
constexpr double kTolP = kClosedTolP, kTolR = kClosedTolR;

// Adds q when `reaches(q)` (the forward model puts the tool on the target), brought within the
// limits where it fits them and marked within_limits then (fit_limits). A stroke a hair outside its
// limit is clamped onto it by fit_limits' tolerance (1e-12 m): for an arm of 1e-30 m that moves the
// tool off the target, and the solution is then returned as it is, marked outside.
template <class Reaches>
void add_if_reaches(ClosedFormSolutions& out, double* q, const JointLimits& lim, const char* posture,
                    Reaches&& reaches) {
  double fitted[ClosedFormSolutions::kMaxDof];
  std::copy(q, q + out.dof, fitted);
  if (fit_limits(fitted, out.dof, lim) && reaches(fitted)) return out.add(fitted, posture, true);
  fit_limits(q, out.dof, JointLimits{{}, {}, lim.prismatic});  // as without limits: revolute angles wrapped
  if (reaches(q)) out.add(q, posture, false);
}

// The tip of a planar 2R (links a1, a2) at (t1, t2) is within tol of (x, y).
bool planar_tip_near(double a1, double a2, double t1, double t2, double x, double y, double tol) {
  return std::hypot(a1 * std::cos(t1) + a2 * std::cos(t1 + t2) - x, a1 * std::sin(t1) + a2 * std::sin(t1 + t2) - y) <=
         tol;
}

// The elbow of a 2R with links a1, a2 whose tip is w from the first joint: c = cos, s = |sin| of
// its angle, from the factored forms
//   1 - c = ((a1 + a2)^2 - w^2) / (2 a1 a2),   1 + c = (w^2 - (a1 - a2)^2) / (2 a1 a2),
// which do not cancel near the stretched or folded elbow: c from the squares is off by ~1e-16, and
// sqrt(1 - c^2) then by ~1e-8 (a1 = a2, the tip 4e-8 from the first joint came out on it). Returns
// false when out of reach by more than kCosEps; `singular` within kCosEps of |c| = 1 (one
// solution), where a pose a hair out of reach is clamped onto the stretched or folded arm.
bool elbow_angle(double a1, double a2, double w, double& c, double& s, bool& singular) {
  const double d = std::abs(a1 - a2);
  const double omc = (a1 + a2 - w) * (a1 + a2 + w) / (2.0 * a1 * a2);
  const double opc = (w - d) * (w + d) / (2.0 * a1 * a2);
  if (!(omc >= -kCosEps && opc >= -kCosEps)) return false;  // also NaN, and inf from a huge w
  singular = omc <= kCosEps || opc <= kCosEps;
  c = omc < opc ? 1.0 - std::max(0.0, omc) : std::max(0.0, opc) - 1.0;
  s = std::sqrt(std::max(0.0, omc) * std::max(0.0, opc));
  return true;
}

const char* singular_elbow(double c) { return c > 0 ? "elbow straight" : "elbow folded"; }

// Within kCosEps of stretched or folded (elbow_angle's `singular`) the two elbows of a 2R (links
// a1, a2 <= 1, the point w from the first joint, the elbow's cosine c and |sine| s) coincide, their
// angles within ~1e-6, and one is returned; unless their first angles still differ, by
// 2 atan2(a2 s, |a1 + a2 c|): up to pi for a folded elbow of near-equal links with the point near
// the first joint (links 0.5 and 0.5, the point 1.2e-7 from the joint: the pose's own elbow was the
// one left out, and under limits the one kept could be outside them). Apart when that exceeds 1e-5,
// unless s is rounding (the folded side's factor of s^2, (w - |a1 - a2|) (w + |a1 - a2|), carries
// ~eps (w + |a1 - a2|)) or the point is on the first joint, where the first angle is free.
bool elbows_apart(double a1, double a2, double w, double c, double s) {
  const double d = std::abs(a1 - a2);
  return (w - d) * (w + d) > 64.0 * std::numeric_limits<double>::epsilon() * (w + d) && w * w >= 1e-24 &&
         2.0 * std::atan2(a2 * s, std::abs(a1 + a2 * c)) > 1e-5;
}

// The planar 2R solutions (theta1, theta2) of links a1, a2 for the point (x, y), algebraically:
// s2 = +sqrt (elbow down) then -sqrt (elbow up); one when singular. Returns the count and, for
// solution k, theta_i = atan2(yx[k][i][0], yx[k][i][1]) (the arc tangents are the caller's: one
// at a time, or several solutions' in one vectorised pass).
int planar_2r_args(double a1, double a2, double x, double y, double yx[2][2][2], const char* label[2],
                   bool& singular) {
  // In units of the longer link (the angles do not change): the squares below neither overflow
  // for huge arms nor underflow for tiny ones.
  const double unit = std::max(a1, a2);
  a1 /= unit, a2 /= unit, x /= unit, y /= unit;
  double c2, sin2;
  singular = false;
  // |(x, y)| without std::hypot: a point within an arm's reach, far from overflow and underflow.
  const double w = std::sqrt(x * x + y * y);
  if (!elbow_angle(a1, a2, w, c2, sin2, singular)) return 0;
  const int count = singular && !elbows_apart(a1, a2, w, c2, sin2) ? 1 : 2;
  for (int k = 0; k < count; ++k) {
    const double s2 = k == 0 ? sin2 : -sin2;
    const double k1 = a1 + a2 * c2, k2 = a2 * s2;
    // s1, c1 share the positive denominator x^2 + y^2: atan2 does not need it.
    yx[k][0][0] = k1 * y - k2 * x, yx[k][0][1] = k1 * x + k2 * y;
    yx[k][1][0] = s2, yx[k][1][1] = c2;
    label[k] = count == 1 ? singular_elbow(c2) : (k == 0 ? "elbow down" : "elbow up");
  }
  // The base angle is free when the point is on the first axis (x = y = 0, a1 = a2).
  if (x * x + y * y < 1e-24) singular = true;
  return count;
}

// planar_2r_args with libm's atan2: th[k] = (theta1, theta2) of solution k.
int planar_2r_solve(double a1, double a2, double x, double y, double th[2][2], const char* label[2],
                    bool& singular) {
  double yx[2][2][2];
  const int count = planar_2r_args(a1, a2, x, y, yx, label, singular);
  for (int k = 0; k < count; ++k)
    for (int i = 0; i < 2; ++i) th[k][i] = std::atan2(yx[k][i][0], yx[k][i][1]);
  return count;
}

Eigen::Matrix3d rot_x(double a) {
  Eigen::Matrix3d m;
  const double c = std::cos(a), s = std::sin(a);
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}

struct ArmSolution {
  double q[3];
  int shoulder, elbow;  // posture_label's indices
};

// The arm's solutions (q1, q2, q3) putting the wrist centre (origin of frame 4; the tip for the
// anthropomorphic arm) at p, written to out (at most 4); returns their count. In frame 1 the wrist is at
//   (a2 c2 + a3 c23 - d4 s23, a2 s2 + a3 s23 + d4 c23, d3),
// so with R = a1 + a2 c2 + a3 c23 - d4 s23:  px = c1 R + d3 s1,  py = s1 R - d3 c1,  pz - d1 = a2 s2 + ...
// R = +-sqrt(px^2 + py^2 - d3^2) (shoulder right / left), q1 = atan2(py, px) + atan2(d3, R); then
// a planar 2R in (R - a1, pz - d1) with links a2 and L = |(a3, d4)| at an angle offset
// psi = atan2(d4, a3).
int arm_solve(const ArmGeometry& g, const Eigen::Vector3d& p, bool& singular, ArmSolution out[4]) {
  const double L = std::hypot(g.a3, g.d4);
  // In units of the arm's longest length, as in planar_2r_solve (no overflow or underflow).
  const double unit = std::max({g.a2, L, std::abs(g.d3), std::abs(g.a1)});
  const double px = p.x() / unit, py = p.y() / unit, d3 = g.d3 / unit;
  const double rho2 = px * px + py * py;
  const double disc = rho2 - d3 * d3;
  if (!(disc >= -kCosEps * std::max(1.0, rho2))) return 0;  // also when rho2 overflowed to inf - inf
  const double rmag = std::sqrt(std::max(0.0, disc)) * unit;
  // r = 0: both shoulders coincide (and with d3 = 0, q1 is free: 0 is returned).
  const bool shoulder_singular = rmag < 1e-12 * unit;
  const double z = p.z() - g.d1;
  const int sides = shoulder_singular ? 1 : 2;
  // Every arc tangent in one vectorised pass: atan2(py, px), psi = atan2(d4, a3), atan2(d3, r) of
  // each shoulder, then the planar 2R's (theta1, theta2) of each shoulder's elbows.
  double y[12], x[12], t[12];
  y[0] = p.y(), x[0] = p.x(), y[1] = g.d4, x[1] = g.a3;
  const char* lab[2][2];
  int n[2] = {0, 0};
  bool elbow_singular[2] = {false, false};
  for (int side = 0; side < sides; ++side) {
    const double R = side == 0 ? rmag : -rmag;
    y[2 + side] = g.d3, x[2 + side] = R;
    double yx[2][2][2];
    n[side] = planar_2r_args(g.a2, L, R - g.a1, z, yx, lab[side], elbow_singular[side]);
    for (int k = 0; k < n[side]; ++k)
      for (int i = 0; i < 2; ++i) y[4 + 4 * side + 2 * k + i] = yx[k][i][0], x[4 + 4 * side + 2 * k + i] = yx[k][i][1];
  }
  vmath::atan2(y, x, t, 4 + 4 * sides);
  const double psi = t[1];
  int count = 0;
  for (int side = 0; side < sides; ++side) {
    const double r = (side == 0 ? rmag : -rmag) - g.a1;  // the wrist's x from joint 2, in frame 1
    const double q1 = t[0] + t[2 + side];
    for (int k = 0; k < n[side]; ++k) {
      const double th1 = t[4 + 4 * side + 2 * k], th2 = t[4 + 4 * side + 2 * k + 1];
      ArmSolution& s = out[count++];
      s.q[0] = q1;
      s.q[1] = th1;
      s.q[2] = th2 - psi;
      s.shoulder = shoulder_singular ? 2 : 1 - side;  // side 0: R > 0, shoulder right
      if (n[side] == 1) {
        s.elbow = th2 > 1.0 ? 3 : 2;  // folded (theta' = pi) or straight (0)
      } else {
        // Elbow above the shoulder-wrist line: sin(theta') < 0 when the wrist is in front of joint
        // 2 (r > 0).
        // theta' = atan2(s2, c2) with s2 = +-sqrt(...) != 0 here: sin(theta') has the sign of s2,
        // negative for the second solution of planar_2r_args (k = 1).
        const bool up = (k == 1) != (r < 0);
        s.elbow = up ? 0 : 1;
      }
    }
    singular = singular || elbow_singular[side] || shoulder_singular;
  }
  return count;
}

// One step F <- F A of a standard DH chain, A = Rz(theta) Tz(d) Tx(a) Rx(alpha) with alpha 0,
// +pi/2 or -pi/2 (twist = 0, +1, -1: Rx then only swaps columns), from cos and sin of theta:
// 18 products where a general 4 x 4 product takes 64.
inline __attribute__((always_inline)) void dh_step(Rigid& F, double a, double d, int twist, double ct, double st) {
  const Eigen::Vector3d x = ct * F.R.col(0) + st * F.R.col(1), y = ct * F.R.col(1) - st * F.R.col(0);
  const Eigen::Vector3d z = F.R.col(2);
  F.p += a * x + d * z;
  F.R.col(0) = x;
  if (twist == 0) {
    F.R.col(1) = y;
  } else if (twist > 0) {  // Rx(pi/2): y' = z, z' = -y
    F.R.col(1) = z, F.R.col(2) = -y;
  } else {  // Rx(-pi/2): y' = -z, z' = y
    F.R.col(1) = -z, F.R.col(2) = y;
  }
}

// Tool frame of the arm of ArmGeometry (standard DH, the PUMA layout) with a spherical wrist and a
// tool offset d6, from the joints' cosines c and sines s.
Rigid wrist_arm_fk(const ArmGeometry& g, double d6, const double* c, const double* s) {
  Rigid F;
  dh_step(F, g.a1, g.d1, +1, c[0], s[0]);
  dh_step(F, g.a2, 0, 0, c[1], s[1]);
  dh_step(F, g.a3, g.d3, -1, c[2], s[2]);
  dh_step(F, 0, g.d4, +1, c[3], s[3]);
  dh_step(F, 0, 0, -1, c[4], s[4]);
  dh_step(F, 0, d6, 0, c[5], s[5]);
  return F;
}

// Frame 3 of the anthropomorphic arm (rows (0, pi/2, d1), (a2, 0, 0), (a3, 0, 0)) at q.
Rigid arm_fk(const ArmGeometry& g, const double* q) {
  Rigid F;
  dh_step(F, g.a1, g.d1, +1, std::cos(q[0]), std::sin(q[0]));
  dh_step(F, g.a2, 0, 0, std::cos(q[1]), std::sin(q[1]));
  dh_step(F, g.a3, 0, 0, std::cos(q[2]), std::sin(q[2]));
  return F;
}


}  // namespace

void check_length(double v, const char* name, bool positive) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(name) + ": must be finite");
  if (positive && !(v > 0)) throw std::invalid_argument(std::string(name) + ": must be positive");
}

double ArmGeometry::size(double d6) const {
  return std::abs(a1) + std::abs(d1) + a2 + std::abs(a3) + std::abs(d3) + std::abs(d4) + std::abs(d6);
}

void ArmGeometry::validate() const {
  check_length(a1, "a1", false);
  check_length(d1, "d1", false);
  check_length(a2, "a2", true);
  check_length(a3, "a3", false);
  check_length(d3, "d3", false);
  check_length(d4, "d4", false);
  if (a3 == 0 && d4 == 0) throw std::invalid_argument("a3, d4: the forearm needs a length (a3 or d4 non-zero)");
}

ClosedFormSolutions ik_planar_rp(double px, double py, const JointLimits& limits) {
  ClosedFormSolutions out;
  out.dof = 2;
  JointLimits lim = limits;
  if (lim.prismatic.empty()) lim.prismatic = {false, true};
  const double d = std::hypot(px, py);
  const auto reaches = [&](const double* q) {
    return std::hypot(q[1] * std::cos(q[0]) - px, q[1] * std::sin(q[0]) - py) <= kTolP * d;
  };
  // Only the origin itself leaves theta1 free: any other point, however near, has its direction.
  if (d == 0) {
    double q[2] = {0.0, 0.0};
    out.singular = true;
    add_if_reaches(out, q, lim, "origin (theta1 free)", reaches);
    return out;
  }
  const double th = std::atan2(py, px);
  double fwd[2] = {th, d}, back[2] = {th + kPi, -d};
  add_if_reaches(out, fwd, lim, "stroke forward", reaches);
  add_if_reaches(out, back, lim, "stroke backward", reaches);
  return out;
}

ClosedFormSolutions ik_planar_2r(double a1, double a2, double px, double py, const JointLimits& limits) {
  check_length(a1, "a1", true);
  check_length(a2, "a2", true);
  ClosedFormSolutions out;
  out.dof = 2;
  double th[2][2];
  const char* lab[2];
  const int n = planar_2r_solve(a1, a2, px, py, th, lab, out.singular);
  const auto reaches = [&](const double* q) { return planar_tip_near(a1, a2, q[0], q[1], px, py, kTolP * (a1 + a2)); };
  for (int k = 0; k < n; ++k) add_if_reaches(out, th[k], limits, lab[k], reaches);
  return out;
}

ClosedFormSolutions ik_planar_3r(double a1, double a2, double a3, double px, double py, double phi,
                                 bool geometric, const JointLimits& limits) {
  check_length(a1, "a1", true);
  check_length(a2, "a2", true);
  check_length(a3, "a3", false);
  ClosedFormSolutions out;
  out.dof = 3;
  // phi as the forward model sees it, through its cosine and sine: for a huge phi (1e300),
  // remainder by the double 2 pi and cos/sin's exact reduction disagree.
  phi = std::atan2(std::sin(phi), std::cos(phi));
  // The wrist point W, origin of frame 2 (the IK course): p_W = p - a3 (cos phi, sin phi).
  const double wx = px - a3 * std::cos(phi), wy = py - a3 * std::sin(phi);
  const auto reaches = [&](const double* q) {
    const double t = q[0] + q[1] + q[2];
    return planar_tip_near(a1, a2, q[0], q[1], px - a3 * std::cos(t), py - a3 * std::sin(t),
                           kTolP * (a1 + a2 + std::abs(a3))) &&
           std::abs(std::cos(t) - std::cos(phi)) <= kTolR && std::abs(std::sin(t) - std::sin(phi)) <= kTolR;
  };
  if (!geometric) {
    double th[2][2];
    const char* lab[2];
    const int n = planar_2r_solve(a1, a2, wx, wy, th, lab, out.singular);
    for (int k = 0; k < n; ++k) {
      double q[3] = {th[k][0], th[k][1], phi - th[k][0] - th[k][1]};
      add_if_reaches(out, q, limits, lab[k], reaches);
    }
    return out;
  }
  // Geometric method: law of cosines in the triangle (O, elbow, W), then theta1 = alpha -+ beta;
  // in units of the longer link, as planar_2r_solve.
  const double unit = std::max(a1, a2), b1 = a1 / unit, b2 = a2 / unit;
  const double ux = wx / unit, uy = wy / unit, w2 = ux * ux + uy * uy, w = std::sqrt(w2);
  double c2, s2;
  bool elbow_singular = false;
  if (!elbow_angle(b1, b2, w, c2, s2, elbow_singular)) return out;
  const double alpha = std::atan2(uy, ux);
  double beta = 0.0;
  if (w > 1e-12 && elbow_singular) {
    // W (nearly) on the line of link 1: acos of the rounded cosine near -+1 would be off by up to
    // ~1e-6 (acos(1 - e) ~ sqrt(2 e)); the same angle from the elbow's accurate sine instead.
    beta = std::atan2(b2 * s2, b1 + b2 * c2);
  } else if (w > 1e-12) {
    const double cb = (w2 + b1 * b1 - b2 * b2) / (2.0 * b1 * w);
    beta = std::acos(std::min(1.0, std::max(-1.0, cb)));
  }
  // W on the first axis (a1 = a2): theta1 is free, 0 is returned.
  out.singular = elbow_singular || w <= 1e-12;
  const double t2 = std::atan2(s2, c2);  // not acos: exact near 0 and pi too
  const int count = elbow_singular && !elbows_apart(b1, b2, w, c2, s2) ? 1 : 2;
  for (int k = 0; k < count; ++k) {
    // Elbow down: theta2 in (0, pi), theta1 = alpha - beta; elbow up: theta2 < 0, alpha + beta.
    const double theta2 = k == 0 ? t2 : -t2;
    const double theta1 = w > 1e-12 ? (k == 0 ? alpha - beta : alpha + beta) : 0.0;
    double q[3] = {theta1, theta2, phi - theta1 - theta2};
    add_if_reaches(out, q, limits, count == 1 ? singular_elbow(c2) : (k == 0 ? "elbow down" : "elbow up"), reaches);
  }
  return out;
}

ClosedFormSolutions ik_anthropomorphic(const ArmGeometry& arm, const Eigen::Vector3d& p,
                                       const JointLimits& limits) {
  arm.validate();
  ClosedFormSolutions out;
  out.dof = 3;
  const auto reaches = [&](const double* q) {
    return (arm_fk(arm, q).p - p).norm() <= kTolP * arm.size();
  };
  ArmSolution arms[4];
  const int n = arm_solve(arm, p, out.singular, arms);
  for (int k = 0; k < n; ++k) add_if_reaches(out, arms[k].q, limits, posture_label(arms[k].shoulder, arms[k].elbow, -1), reaches);
  return out;
}

namespace {

// The candidates of the spherical-wrist arm for the frame T of its DH model (tool offset d6): up to
// 8 joint vectors of DH angles, each with posture_label's shoulder and elbow indices, its wrist's flip
// (0 or 1) and whether the wrist is singular (then q4 = 0 or pi: q4 + q6 alone is fixed).
struct WristCandidates {
  double q[8][6];
  int shoulder[8], elbow[8], flip[8];
  bool wrist_singular[8];
  int n = 0;
  bool singular = false;
};

// In stages, each stage's sines, cosines and arc tangents for every arm solution or candidate in
// one vectorised pass (fast_math.hpp): the arm (q1, q2, q3), R03 from cos and sin of q1 and
// q2 + q3, the wrist's q4, then q5, q6.
void spherical_candidates(const ArmGeometry& arm, double d6, const Rigid& T, WristCandidates& out) {
  const Eigen::Vector3d pw = T.p - d6 * T.R.col(2);
  ArmSolution arms[4];
  const int na = arm_solve(arm, pw, out.singular, arms);
  double ang[16], sn[16], cs[16];
  for (int a = 0; a < na; ++a) ang[2 * a] = arms[a].q[0], ang[2 * a + 1] = arms[a].q[1] + arms[a].q[2];
  vmath::sincos(ang, sn, cs, 2 * na);
  // R36 = Rz(q4) Rx(pi/2) Rz(q5) Rx(-pi/2) Rz(q6) = Rz(q4) Ry(-q5) Rz(q6): third column
  // (-c4 s5, -s4 s5, c5). Given q4, N = Rz(-q4) R36 = Ry(-q5) Rz(q6) gives q5 (third column
  // (-s5, 0, c5)) and q6 (second row (s6, c6, 0)).
  const Eigen::Matrix3d rx_p = rot_x(kPi / 2), rx_m = rot_x(-kPi / 2);
  Eigen::Matrix3d M[4];
  double my[4], mx[4], q4[8];
  bool wrist_singular[4];
  for (int a = 0; a < na; ++a) {
    // R03 = Rz(q1) Rx(pi/2) Rz(q2 + q3) Rx(-pi/2), the twists' cosines as the DH rows have them
    // (6e-17, not 0): near the wrist singularity M(0, 2) and M(1, 2) are tiny and q4 follows them.
    Eigen::Matrix3d Rz1, Rz23;
    Rz1 << cs[2 * a], -sn[2 * a], 0, sn[2 * a], cs[2 * a], 0, 0, 0, 1;
    Rz23 << cs[2 * a + 1], -sn[2 * a + 1], 0, sn[2 * a + 1], cs[2 * a + 1], 0, 0, 0, 1;
    const Eigen::Matrix3d R03 = Rz1 * rx_p * Rz23 * rx_m;
    M[a].noalias() = R03.transpose() * T.R;
    wrist_singular[a] = std::hypot(M[a](0, 2), M[a](1, 2)) < 1e-10;
    out.singular = out.singular || wrist_singular[a];
    my[a] = -M[a](1, 2), mx[a] = -M[a](0, 2);
  }
  vmath::atan2(my, mx, q4, na);
  for (int a = na - 1; a >= 0; --a) {
    const double v = wrist_singular[a] ? 0.0 : q4[a];  // in [-pi, pi], and so is the flip's
    q4[2 * a] = v, q4[2 * a + 1] = v > 0 ? v - kPi : v + kPi;
  }
  vmath::sincos(q4, sn, cs, 2 * na);
  double y56[16], x56[16], q56[16];
  for (int k = 0; k < 2 * na; ++k) {
    const Eigen::Matrix3d& m = M[k / 2];
    const double c = cs[k], s = sn[k];  // N = Rz(-q4) M: rows c M0 + s M1, c M1 - s M0, M2
    y56[2 * k] = -(c * m(0, 2) + s * m(1, 2)), x56[2 * k] = m(2, 2);
    y56[2 * k + 1] = c * m(1, 0) - s * m(0, 0), x56[2 * k + 1] = c * m(1, 1) - s * m(0, 1);
  }
  vmath::atan2(y56, x56, q56, 4 * na);
  out.n = 2 * na;
  for (int k = 0; k < out.n; ++k) {
    const ArmSolution& a = arms[k / 2];
    double* v = out.q[k];
    v[0] = a.q[0], v[1] = a.q[1], v[2] = a.q[2], v[3] = q4[k], v[4] = q56[2 * k], v[5] = q56[2 * k + 1];
    out.shoulder[k] = a.shoulder, out.elbow[k] = a.elbow, out.flip[k] = k % 2;
    out.wrist_singular[k] = wrist_singular[k / 2];
  }
}

}  // namespace

ClosedFormSolutions ik_spherical_wrist_6r(const ArmGeometry& arm, double d6, const Rigid& T,
                                          const JointLimits& limits) {
  arm.validate();
  check_length(d6, "d6", false);
  ClosedFormSolutions out;
  out.dof = 6;
  WristCandidates c;
  spherical_candidates(arm, d6, T, c);
  out.singular = c.singular;
  // The candidates within the limits are checked by the DH model, in their order.
  double angles[48], cs[48], sn[48];
  bool within[8];
  for (int k = 0; k < c.n; ++k) {
    within[k] = fit_limits(c.q[k], 6, limits);
    std::copy(c.q[k], c.q[k] + 6, angles + 6 * k);
  }
  vmath::sincos(angles, sn, cs, 6 * c.n);
  const double size = arm.size(d6);
  for (int k = 0; k < c.n; ++k) {
    const Rigid F = wrist_arm_fk(arm, d6, cs + 6 * k, sn + 6 * k);
    if (closed_reaches(F, T, size))
      out.add(c.q[k], posture_label(c.shoulder[k], c.elbow[k], c.flip[k]), within[k]);
  }
  return out;
}

ClosedFormSolutions ik_spherical(const SphericalArm& sa, const Chain& chain, const Rigid& T,
                                 const JointLimits& limits, int* slot) {
  ClosedFormSolutions out;
  out.dof = 6;
  WristCandidates c;
  spherical_candidates(sa.arm, 0.0, sa.base.inverse() * T * sa.tool.inverse(), c);
  out.singular = c.singular;
  // The chain's joints of each candidate: one per arm solution where the wrist is singular (q4 = 0
  // of the continuum, labelled "wrist singular" as closed_solve labels it).
  double q[8][6];
  int keep[8], m = 0;
  for (int k = 0; k < c.n; ++k) {
    if (c.wrist_singular[k] && c.flip[k]) continue;
    for (int i = 0; i < 6; ++i) q[m][i] = sa.scale[i] * (c.q[k][i] - sa.theta[i]);
    keep[m++] = k;
  }
  bool within[8];
  fit_limits_rows(q[0], m, 6, limits, within);
  Rigid F[8];
  chain.fk_few(q[0], m, F);
  for (int j = 0; j < m; ++j) {
    if (!closed_reaches(F[j], T, sa.size)) continue;
    const int k = keep[j], wrist = c.wrist_singular[k] ? 2 : c.flip[k];
    if (slot) slot[out.count()] = posture_slot(c.shoulder[k], c.elbow[k], wrist);
    out.add(q[j], posture_label(c.shoulder[k], c.elbow[k], wrist), within[j]);
  }
  return out;
}

void ik_spherical_wrist_6r_path(const ArmGeometry& arm, double d6, const Rigid* targets, long count,
                                const double* q0, const JointLimits& limits, double* q_out, bool* ok,
                                bool* reachable, Progress* progress) {
  arm.validate();
  check_length(d6, "d6", false);
  // Angles are shifted at most to |v| <= 2^20 rad (~167,000 turns): there a double holds them to
  // 1.2e-10 rad (and the double 2 pi's error, times the turns, stays below that), so the shifted
  // joints still reach the target within the verified tolerance. Near 1e17 the rounding of
  // v + 2 pi k would leave the angle, and the pose, arbitrary.
  constexpr double kMaxShifted = 1048576.0;
  double prev[6];
  std::copy(q0, q0 + 6, prev);
  for (long k = 0; k < count; ++k) {
    if (k % 256 == 0) report(progress, k, count);
    ClosedFormSolutions s = ik_spherical_wrist_6r(arm, d6, targets[k], limits);
    // Each solution's angles shifted by the whole turns that bring them nearest the previous
    // joints, as far as the limits and kMaxShifted allow (v itself is within both, so 0 turns
    // always is).
    for (int r = 0; r < s.count(); ++r)
      for (int i = 0; i < 6; ++i) {
        double& v = s.row(r)[i];
        const double lo = std::max(-kMaxShifted, limits.lower.size() ? limits.lower(i) : -INFINITY);
        const double hi = std::min(kMaxShifted, limits.upper.size() ? limits.upper(i) : INFINITY);
        const double fewest = std::min(0.0, std::ceil((lo - v) / (2 * kPi)));
        const double most = std::max(0.0, std::floor((hi - v) / (2 * kPi)));
        const double turns = std::clamp(std::round((prev[i] - v) / (2 * kPi)), fewest, most);
        v += 2 * kPi * turns;
      }
    const int best = nearest_solution(s, prev);
    ok[k] = best >= 0;
    reachable[k] = s.count() > 0;
    if (best >= 0) std::copy(s.row(best), s.row(best) + 6, prev);
    std::copy(prev, prev + 6, q_out + 6 * k);
  }
}

int nearest_solution(const ClosedFormSolutions& s, const double* q) {
  int best = -1;
  double best_d = 0;
  for (int k = 0; k < s.count(); ++k) {
    if (!s.within_limits[k]) continue;
    double d = 0;
    for (int i = 0; i < s.dof; ++i) {
      const double e = s.row(k)[i] - q[i];
      d += e * e;
    }
    if (best < 0 || d < best_d) best = k, best_d = d;
  }
  return best;
}

}  // namespace robokin

// ---------------------------------------------------------------------------------------------
// The Universal Robots family: three parallel axes (2, 3, 4).
namespace robokin {

// Slot k is posture_slot's k: shoulder (k / 4), elbow (k / 2 % 2), wrist (k % 2).
const char* const kURPostures[8] = {
    posture_label(0, 0, 0), posture_label(0, 0, 1), posture_label(0, 1, 0), posture_label(0, 1, 1),
    posture_label(1, 0, 0), posture_label(1, 0, 1), posture_label(1, 1, 0), posture_label(1, 1, 1),
};

namespace {
// Near the wrist's singularity (joint 5 near 0 or pi) q234 = atan2(-M(1, 2), -M(0, 2)) is known only
// to the rounding of q1 and M over w = |(M(0, 2), M(1, 2))| = |sin q5| (~80 eps / w measured; 500
// eps / w next to the shoulder's singularity, where q1 is less precise).
// Where the elbow is straight or folded, the origin 4 it gives (P + d5 (-sin q234, cos q234) in
// frame 1) fell a hair outside the planar 2R's reach, and the pose's own solutions were lost (UR5 at
// q = (0, 2, 0, 0, 1e-6, 0)), or a hair inside, and they came back with the elbow bent by up to
// ~1e-2 (q5 = 3e-10). Moves t = q234 to the nearest angle that puts origin 4 on the reach's edge
// (|a2| + |a3| or ||a2| - |a3|| from axis 2) when the move is within 1e-13 / w (the wrist's frame
// turned by at most 1e-13); false, t unchanged, otherwise. An elbow bent by less than about
// sqrt(1e-13 / w) is then returned straight: it is that far from straight by rounding alone.
bool onto_reach(const Eigen::Vector3d& P, double d5, double a2, double a3, double w, double& t) {
  // |origin 4|^2 = rho^2 + d5^2 + 2 d5 rho cos(t + beta), with P = rho (sin beta, cos beta).
  const double rho = std::hypot(P.x(), P.y()), beta = std::atan2(P.x(), P.y());
  const double x = P.x() - d5 * std::sin(t), y = P.y() + d5 * std::cos(t);
  const double edge = x * x + y * y > a2 * a2 + a3 * a3 ? a2 + a3 : std::abs(a2 - a3);  // beyond or within
  const double den = 2.0 * d5 * rho;
  if (!(std::abs(den) > 0.0)) return false;
  const double cv = (edge * edge - rho * rho - d5 * d5) / den;
  if (!(std::abs(cv) <= 1.0)) return false;
  const double a = std::acos(cv);
  const double up = wrap_angle(a - beta - t), down = wrap_angle(-a - beta - t);  // the two moves
  const double dt = std::abs(up) <= std::abs(down) ? up : down;
  if (!(std::abs(dt) * w <= 1e-13)) return false;
  t += dt;
  return true;
}
}  // namespace

namespace {

// One ik_ur call's stages, on the stack (no allocation, nothing initialised that a stage does not
// write): each stage reads the previous ones' fields and computes its arc tangents, sines and
// cosines in one vectorised pass (fast_math.hpp). Td, the frame A1 ... A5 Rz(q6) of the bare DH arm
// (its origin is the wrist centre), is the caller's.
struct URStages {
  // The arm's unit (the longest of a2, a3, d4, d5), |a2| and |a3|.
  double unit, a2, a3;
  // Shoulders (side 0 left, 1 right; one when singular): q1 and its sine and cosine.
  bool shoulder_singular;
  int sides;
  double q1[2], s1[2], c1[2];
  // Per side: R16 = Rz(q234) Ry(-q5) Rz(q6) (M), the wrist centre in frame 1 (P), the wrist's
  // singularity and q234's arc tangent.
  Eigen::Matrix3d M[2];
  Eigen::Vector3d P[2];
  bool wrist_singular[2];
  double tw[2];
  // The (shoulder, wrist) pairs: q234 of each, its sine and cosine.
  int pairs, pair_side[4], pair_flip[4];
  double q234[4], s234[4], c234[4];
  // Per pair: atan2 arguments and results of q5, q6 (2) and of the planar 2R's solutions (up to
  // 2 x 2), origin 4 in frame 1 (X, Y), the 2R's solution count and elbow singularity.
  double y[24], x[24], t[24], X[4], Y[4];
  int nk[4];
  const char* lab[4][2];
  bool elbow_singular[4];
  // The candidates: joints, posture label, slot of rk.closed.ur_batch's 8.
  double cand[8][6];
  const char* posture[8];
  int cand_slot[8], m;
};

// q1 of each shoulder. Axis 1: z1 = (s1, -c1, 0) and z1 . p = d4 (joints 2 to 5 move the wrist
// centre in a plane d4 from the one through axis 1): r sin(q1 - phi) = d4, two solutions
// x1 . p = +-h. False when the wrist centre is out of reach of both.
inline __attribute__((always_inline)) bool ur_shoulders(const URArm& arm, const Rigid& Td, URStages& s,
                                                        ClosedFormSolutions& out) {
  const Eigen::Vector3d& p = Td.p;
  const double unit = std::max({std::abs(arm.a2), std::abs(arm.a3), std::abs(arm.d4), std::abs(arm.d5)});
  s.unit = unit;
  // |p_xy| without std::hypot (glibc's takes several square roots): the squares of a point an arm
  // of a sane size reaches are far from overflow and underflow (an arm near 1e154 finds nothing).
  const double r = std::sqrt(p.x() * p.x() + p.y() * p.y()) / unit, d4 = std::abs(arm.d4) / unit;
  const double disc = (r - d4) * (r + d4);
  if (!(disc >= -kCosEps * std::max(1.0, r * r))) return false;
  const double h = std::sqrt(std::max(0.0, disc)) * unit;
  // disc carries the rounding of r^2 (~1e-16): h, its square root, is then ~1e-8 where the two
  // shoulders coincide, and the two q1 differ by ~h / d4.
  s.shoulder_singular = disc <= 1e-13 * std::max(1.0, r * r);
  if (s.shoulder_singular) out.singular = true;
  s.sides = s.shoulder_singular ? 1 : 2;
  s.a2 = std::abs(arm.a2), s.a3 = std::abs(arm.a3);
  double ya[3] = {p.y(), arm.d4, arm.d4}, xa[3] = {p.x(), -h, h}, ta[3];  // shoulder left: x1 = -h
  vmath::atan2(ya, xa, ta, 1 + s.sides);
  const double phi = r > 0 ? ta[0] : 0.0;  // r = 0 (d4 = 0): q1 free, 0 chosen
  for (int side = 0; side < s.sides; ++side) s.q1[side] = phi + ta[1 + side];
  vmath::sincos(s.q1, s.s1, s.c1, s.sides);
  return true;
}

// Per shoulder: the wrist's frame M = R16 and centre P seen from frame 1, and q234's arc tangent.
inline __attribute__((always_inline)) void ur_wrists(const URArm& arm, const Rigid& Td, URStages& s,
                                                     ClosedFormSolutions& out) {
  double yw[2], xw[2];
  for (int side = 0; side < s.sides; ++side) {
    // Rz(q1) Rx(pi/2), with cos(pi/2) as the chain's DH row has it (6e-17, not 0): near the wrist
    // singularity M(0, 2) and M(1, 2) are tiny and q234 follows their rounding.
    Eigen::Matrix3d Rz1;
    Rz1 << s.c1[side], -s.s1[side], 0, s.s1[side], s.c1[side], 0, 0, 0, 1;
    const Eigen::Matrix3d R01 = Rz1 * rot_x(kPi / 2);
    s.M[side].noalias() = R01.transpose() * Td.R;  // R16 = Rz(q234) Ry(-q5) Rz(q6)
    s.P[side].noalias() = R01.transpose() * (Td.p - Eigen::Vector3d(0, 0, arm.d1));
    const Eigen::Matrix3d& M = s.M[side];
    s.wrist_singular[side] = M(0, 2) * M(0, 2) + M(1, 2) * M(1, 2) < 1e-20;  // |.| < 1e-10
    if (s.wrist_singular[side]) out.singular = true;
    yw[side] = -M(1, 2), xw[side] = -M(0, 2);
  }
  vmath::atan2(yw, xw, s.tw, s.sides);
}

// q234 of each (shoulder, wrist) pair: the wrist's two flips, or one representative when the wrist
// is singular.
inline __attribute__((always_inline)) void ur_pairs(const URArm& arm, URStages& s) {
  int pairs = 0;  // a local, as m in ur_candidates
  for (int side = 0; side < s.sides; ++side)
    for (int flip = 0; flip < (s.wrist_singular[side] ? 1 : 2); ++flip) {
      double t;
      if (!s.wrist_singular[side]) {
        t = s.tw[side] + (flip ? kPi : 0.0);
      } else {
        // Axes 2, 3, 4, 6 parallel: q234 is free. The wrist's origin 4 is then on the circle
        // P + d5 (-sin t, cos t); the representative puts it where |W|^2 = a2^2 + a3^2 (the
        // elbow at a right angle) or as near as the circle comes.
        const Eigen::Vector3d& Ps = s.P[side];
        const double rho = std::hypot(Ps.x(), Ps.y());
        const double beta = std::atan2(Ps.x(), Ps.y());
        const double den = 2.0 * arm.d5 * rho;
        t = 0.0;
        if (std::abs(den) > 1e-12 * s.unit * s.unit) {
          const double cv = (s.a2 * s.a2 + s.a3 * s.a3 - rho * rho - arm.d5 * arm.d5) / den;
          t = std::acos(std::clamp(cv, -1.0, 1.0)) - beta;
        }
      }
      s.pair_side[pairs] = side, s.pair_flip[pairs] = flip, s.q234[pairs++] = t;
    }
  s.pairs = pairs;
  vmath::sincos(s.q234, s.s234, s.c234, pairs);
}

// Per pair: the atan2 arguments of q5, q6 and of the planar 2R (links |a2|, |a3|) reaching origin 4,
// then every arc tangent at once.
inline __attribute__((always_inline)) void ur_angles(const URArm& arm, URStages& s, ClosedFormSolutions& out) {
  double* y = s.y;
  double* x = s.x;
  const int pairs = s.pairs;
  for (int j = 0; j < pairs; ++j) {
    const Eigen::Matrix3d& m = s.M[s.pair_side[j]];
    double c = s.c234[j], sn = s.s234[j];  // N = Rz(-q234) M: rows c M0 + s M1, c M1 - s M0, M2
    // Origin 4 in frame 1: (a2 c2 + a3 c23, a2 s2 + a3 s23), a planar 2R (links |a2|, |a3|).
    const Eigen::Vector3d& Ps = s.P[s.pair_side[j]];
    s.X[j] = Ps.x() - arm.d5 * sn, s.Y[j] = Ps.y() + arm.d5 * c;
    double yx[2][2][2];
    const double w2 = m(0, 2) * m(0, 2) + m(1, 2) * m(1, 2);  // sin^2 q5
    if (!s.wrist_singular[s.pair_side[j]] && w2 < 1e-6 && onto_reach(Ps, arm.d5, s.a2, s.a3, std::sqrt(w2), s.q234[j])) {
      c = std::cos(s.q234[j]), sn = std::sin(s.q234[j]);
      s.X[j] = Ps.x() - arm.d5 * sn, s.Y[j] = Ps.y() + arm.d5 * c;
    }
    s.nk[j] = planar_2r_args(s.a2, s.a3, s.X[j], s.Y[j], yx, s.lab[j], s.elbow_singular[j]);
    if (s.elbow_singular[j]) out.singular = true;
    y[6 * j] = -(c * m(0, 2) + sn * m(1, 2)), x[6 * j] = m(2, 2);
    y[6 * j + 1] = c * m(1, 0) - sn * m(0, 0), x[6 * j + 1] = c * m(1, 1) - sn * m(0, 1);
    for (int k = 0; k < s.nk[j]; ++k)
      for (int i = 0; i < 2; ++i) y[6 * j + 2 + 2 * k + i] = yx[k][i][0], x[6 * j + 2 + 2 * k + i] = yx[k][i][1];
    for (int i = 2 + 2 * s.nk[j]; i < 6; ++i) y[6 * j + i] = 0.0, x[6 * j + i] = 1.0;  // unused
  }
  vmath::atan2(y, x, s.t, 6 * pairs);
}

// The candidates: the DH angles of each pair's 2R solutions as the chain's joints, with their
// posture labels and slots.
inline __attribute__((always_inline)) void ur_candidates(const URArm& arm, URStages& s) {
  const double* t = s.t;
  int m = 0;  // a local: the stores below may not reload it
  for (int j = 0; j < s.pairs; ++j) {
    const int side = s.pair_side[j], flip = s.pair_flip[j];
    const double q5 = t[6 * j], q6 = t[6 * j + 1];
    for (int k = 0; k < s.nk[j]; ++k) {
      const double th1 = t[6 * j + 2 + 2 * k], th2 = t[6 * j + 3 + 2 * k];
      // Negative a2, a3 (the UR arms): a c = |a| cos(angle + pi).
      const double q2 = th1 - (arm.a2 < 0 ? kPi : 0.0);
      const double q3 = th2 + ((arm.a2 < 0 ? kPi : 0.0) - (arm.a3 < 0 ? kPi : 0.0));
      int elbow;
      if (s.nk[j] == 1) {
        elbow = s.x[6 * j + 3] > 0 ? 2 : 3;  // cos theta2 > 0 (c2 of planar_2r_args): straight, else folded
      } else {
        // The elbow's side of the line to origin 4: X a2 sin(th1) - Y a2 cos(th1), whose sign is
        // that of X y1 - Y x1 for th1 = atan2(y1, x1).
        const double cross = s.X[j] * s.y[6 * j + 2 + 2 * k] - s.Y[j] * s.x[6 * j + 2 + 2 * k];
        elbow = ((cross > 0) == (s.X[j] >= 0)) ? 0 : 1;
      }
      const double dh[6] = {s.q1[side], q2, q3, s.q234[j] - q2 - q3, q5, q6};
      for (int i = 0; i < 6; ++i) s.cand[m][i] = (dh[i] - arm.theta[i]) * arm.scale[i];
      const int shoulder = s.shoulder_singular ? 2 : side, wrist = s.wrist_singular[side] ? 2 : flip;
      s.posture[m] = posture_label(shoulder, elbow, wrist);
      s.cand_slot[m++] = posture_slot(shoulder, elbow, wrist);
    }
  }
  s.m = m;
}

// The candidates brought within the limits where they fit (marked), checked by the chain's forward
// model together: those that reach T are the answer.
inline __attribute__((always_inline)) void ur_checked(const URArm& arm, const Chain& chain, const Rigid& T,
                                                      const JointLimits& limits, URStages& s, int* slot,
                                                      ClosedFormSolutions& out) {
  bool fits[8];
  fit_limits_rows(s.cand[0], s.m, 6, limits, fits);
  Rigid F[8];
  chain.fk_few(s.cand[0], s.m, F);
  for (int k = 0; k < s.m; ++k) {
    if (!closed_reaches(F[k], T, arm.size)) continue;
    if (slot) slot[out.count()] = s.cand_slot[k];
    out.add(s.cand[k], s.posture[k], fits[k]);
  }
}

}  // namespace

ClosedFormSolutions ik_ur(const URArm& arm, const Chain& chain, const Rigid& T, const JointLimits& limits,
                          int* slot) {
  ClosedFormSolutions out;
  out.dof = 6;
  const Rigid Td = arm.base.inverse() * T * arm.tool.inverse();
  URStages s;
  if (!ur_shoulders(arm, Td, s, out)) return out;
  ur_wrists(arm, Td, s, out);
  ur_pairs(arm, s);
  ur_angles(arm, s, out);
  ur_candidates(arm, s);
  ur_checked(arm, chain, T, limits, s, slot, out);
  return out;
}

void ik_ur_batch(const URArm& arm, const Chain& chain, const Rigid* targets, long count, const JointLimits& limits,
                 double* q_out, bool* within_limits, bool* singular, Progress* progress) {
  closed_batch(
      count, 512, 6, [&](long k, int* slot) { return ik_ur(arm, chain, targets[k], limits, slot); },
      q_out, within_limits, singular, progress);
}

void ik_spherical_batch(const SphericalArm& arm, const Chain& chain, const Rigid* targets, long count,
                        const JointLimits& limits, double* q_out, bool* within_limits, bool* singular,
                        Progress* progress) {
  closed_batch(
      count, 512, 6, [&](long k, int* slot) { return ik_spherical(arm, chain, targets[k], limits, slot); },
      q_out, within_limits, singular, progress);
}

}  // namespace robokin
