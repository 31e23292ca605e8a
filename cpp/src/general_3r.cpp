// General 3R positioning arms: the arm read from a chain, and every inverse solution of a point from
// a trigonometric polynomial in q3.
#include "robokin/general_3r.hpp"
#include "arm_3r.hpp"
#include "robokin/angles.hpp"

#include <Eigen/Eigenvalues>
#include <kdl/segment.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

using namespace arm_3r_model;

[[noreturn]] void not_3r(const std::string& why) { throw std::invalid_argument("chain: not a 3R arm (" + why + ")"); }

// Real roots in [-pi, pi) of a trigonometric polynomial of degree <= 2 known by samples f(k 2pi/8):
// its coefficients by the discrete Fourier transform (exact for that degree), then the roots z on
// the unit circle of z^m f as the eigenvalues of the companion matrix. `identically_zero` when
// every coefficient vanishes.
std::vector<double> trig_roots(const double f[8], bool& identically_zero) {
  std::complex<double> c[3];  // f = sum_k c_k z^k + conj, c_0 real
  double scale = 0;
  for (int k = 0; k <= 2; ++k) {
    std::complex<double> s = 0;
    for (int n = 0; n < 8; ++n) s += f[n] * std::polar(1.0, -2 * kPi * k * n / 8.0);
    c[k] = s / 8.0;
    scale = std::max(scale, std::abs(c[k]));
  }
  std::vector<double> roots;
  identically_zero = !(scale > 0);
  if (identically_zero) return roots;
  int m = 2;
  while (m > 0 && std::abs(c[m]) <= 1e-13 * scale) --m;
  if (m == 0) {
    identically_zero = std::abs(c[0]) <= 1e-13 * scale;
    return roots;
  }
  // z^m f(z) = sum_{k=-m..m} c_k z^(k+m), c_{-k} = conj(c_k): monic companion of degree 2m.
  const int deg = 2 * m;
  std::vector<std::complex<double>> poly(deg + 1);  // poly[j]: coefficient of z^j
  for (int k = -m; k <= m; ++k) poly[k + m] = k >= 0 ? c[k] : std::conj(c[-k]);
  Eigen::MatrixXcd comp = Eigen::MatrixXcd::Zero(deg, deg);
  for (int j = 1; j < deg; ++j) comp(j, j - 1) = 1.0;
  for (int j = 0; j < deg; ++j) comp(j, deg - 1) = -poly[j] / poly[deg];
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(comp, false);
  for (int j = 0; j < deg; ++j) {
    const std::complex<double> z = es.eigenvalues()(j);
    if (std::abs(std::abs(z) - 1.0) < 1e-3) roots.push_back(std::arg(z));
  }
  return roots;
}

bool near_angles(const double* a, const double* b, int n, double tol) {
  for (int i = 0; i < n; ++i)
    if (std::abs(wrap_angle(a[i] - b[i])) > tol) return false;
  return true;
}

}  // namespace

Arm3R arm_3r(const Chain& chain) {
  if (chain.dof() != 3) not_3r("it has " + std::to_string(chain.dof()) + " joints, not 3");
  Arm3R arm;
  Rigid since, after[3];
  int j = -1;
  for (const KDL::Segment& seg : chain.kdl().segments) {
    const KDL::Joint& joint = seg.getJoint();
    if (joint.getType() == KDL::Joint::Fixed) {
      since = since * Rigid::from_kdl(seg.pose(0.0));
      continue;
    }
    ++j;
    if (joint.getType() >= KDL::Joint::TransAxis) not_3r("joint " + std::to_string(j + 1) + " is prismatic");
    const Rigid P0 = Rigid::from_kdl(joint.pose(0.0)), P1 = Rigid::from_kdl(joint.pose(0.5));
    const bool plus = (P1.R - rz(0.5)).cwiseAbs().maxCoeff() < 1e-12;
    const bool minus = (P1.R - rz(-0.5)).cwiseAbs().maxCoeff() < 1e-12;
    if ((P0.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 || P0.p.norm() > 0 || P1.p.norm() > 0 ||
        !(plus || minus))
      not_3r("joint " + std::to_string(j + 1) + " does not turn about the z axis of its frame");
    arm.scale[j] = plus ? 1.0 : -1.0;
    if (j == 0) arm.base = since;
    else after[j - 1] = since;
    since = Rigid::from_kdl(seg.pose(0.0));
  }
  after[2] = since;
  arm.F1 = after[0], arm.F2 = after[1], arm.tip = after[2].p;
  arm.size = arm.F1.p.norm() + arm.F2.p.norm() + arm.tip.norm();
  if (!(arm.size > 0)) not_3r("all its lengths are 0");
  // Axes 1 and 2 the same line: q1 and q2 are one joint.
  const Eigen::Vector3d h = arm.F1.R.row(2).transpose(), g = arm.F1.R.transpose() * arm.F1.p;
  if (std::hypot(h.x(), h.y()) < 1e-12 && std::hypot(g.x(), g.y()) < 1e-12 * arm.size)
    not_3r("joints 1 and 2 turn about the same axis");
  return arm;
}

double det_3r(const Arm3R& arm, double q2, double q3) {
  const double t[3] = {0.0, arm.scale[1] * q2, arm.scale[2] * q3};
  return jacobian(arm, t).determinant() * arm.scale[0] * arm.scale[1] * arm.scale[2];
}

namespace {

// The tool point p seen from joint 1 (pp = Rz(t1) u), reduced to equations in t3: with
// V = Rz(t2) w(t3), the invariants of joint 1 give h_xy . V_xy = C1, g_xy . V_xy = C2 and
// |V_xy| = |w_xy|, one trigonometric polynomial in t3 (of degree 1 when the first two axes are
// parallel or intersect: `degenerate`).
struct Reduced3R {
  const Arm3R& arm;
  Eigen::Vector3d pp, h, g;
  double P2, b2, nh, ng, det, kf;
  Eigen::Matrix2d M;
  bool degenerate;

  Reduced3R(const Arm3R& a, const Eigen::Vector3d& p) : arm(a) {
    pp = arm.base.R.transpose() * (p - arm.base.p);  // = Rz(t1) u
    h = arm.F1.R.row(2).transpose(), g = arm.F1.R.transpose() * arm.F1.p;
    P2 = pp.squaredNorm(), b2 = arm.F1.p.squaredNorm();
    M << h.x(), h.y(), g.x(), g.y();
    nh = std::hypot(h.x(), h.y()), ng = std::hypot(g.x(), g.y());
    det = M.determinant();
    // First two axes parallel (h_xy = 0) or intersecting (g_xy parallel to h_xy): one equation in t3.
    degenerate = !(std::abs(det) > 1e-9 * nh * ng) || nh < 1e-12 || ng < 1e-12 * arm.size;
    kf = nh >= 1e-12 ? (g.x() * h.x() + g.y() * h.y()) / (nh * nh) : 0.0;
  }

  // With V = Rz(t2) w:  h_xy . V_xy = C1,  g_xy . V_xy = C2,  |V_xy| = |w_xy|.
  void eqs(double t3, double& C1, double& C2, Eigen::Vector3d& w) const {
    w = arm.F2.R * (rz(t3) * arm.tip) + arm.F2.p;
    C1 = pp.z() - arm.F1.p.z() - h.z() * w.z();
    C2 = 0.5 * (P2 - w.squaredNorm() - b2) - g.z() * w.z();
  }

  // The polynomial in t3 whose roots are the solutions' t3.
  double residual(double t3) const {
    double C1, C2;
    Eigen::Vector3d w;
    eqs(t3, C1, C2, w);
    if (!degenerate) {
      // |adj(M) C|^2 - det^2 |w_xy|^2: no division by det.
      const double vx = M(1, 1) * C1 - M(0, 1) * C2, vy = -M(1, 0) * C1 + M(0, 0) * C2;
      return (vx * vx + vy * vy - det * det * (w.x() * w.x() + w.y() * w.y())) / (arm.size * arm.size);
    }
    return nh >= 1e-12 ? C2 - kf * C1 : C1;
  }

  // The V_xy of t3: the linear system's one solution, or the line's points at distance |w_xy|
  // (none, one or two) in the degenerate case.
  void v_candidates(double C1, double C2, double rw, std::vector<Eigen::Vector2d>& Vs) const {
    if (!degenerate) {
      Vs.push_back(Eigen::Vector2d(M(1, 1) * C1 - M(0, 1) * C2, -M(1, 0) * C1 + M(0, 0) * C2) / det);
      return;
    }
    const Eigen::Vector2d n = nh >= 1e-12 ? Eigen::Vector2d(h.x(), h.y()) : Eigen::Vector2d(g.x(), g.y());
    const double c = nh >= 1e-12 ? C1 : C2, nn = n.norm();
    const Eigen::Vector2d foot = n * (c / (nn * nn)), perp(-n.y() / nn, n.x() / nn);
    const double d2 = rw * rw - foot.squaredNorm();
    if (d2 < -1e-6 * arm.size * arm.size) return;
    const double d = std::sqrt(std::max(0.0, d2));
    Vs.push_back(foot + d * perp);
    if (d > 0) Vs.push_back(foot - d * perp);
  }
};

// The roots t3 of the reduced polynomial (sampled at 8 angles); one representative, `singular`
// set, when it vanishes identically (a continuum in q3).
std::vector<double> roots_t3(const Reduced3R& red, ClosedFormSolutions& out) {
  double f[8];
  for (int n = 0; n < 8; ++n) f[n] = red.residual(2 * kPi * n / 8.0);
  bool zero = false;
  std::vector<double> t3s = trig_roots(f, zero);
  if (zero) {  // a continuum in q3: one representative
    out.singular = true;
    t3s = {0.0};
  }
  return t3s;
}

// t2 and t1 of a solution from V (and w, u); an angle is 0 where it is free (the point on its
// axis), `singular` then set. Polished by Newton's method on the forward model (the roots carry
// the eigenvalues' rounding).
std::array<double, 3> solve_t2_t1(const Reduced3R& red, const Eigen::Vector3d& p, double t3, const Eigen::Vector3d& w,
                                  double rw, const Eigen::Vector2d& V, ClosedFormSolutions& out) {
  const Arm3R& arm = red.arm;
  double t[3];
  t[2] = t3;
  if (rw < 1e-12 * arm.size) {
    t[1] = 0.0;  // the point on axis 2: q2 free
    out.singular = true;
  } else {
    t[1] = std::atan2(V.y(), V.x()) - std::atan2(w.y(), w.x());
  }
  const Eigen::Vector3d u = arm.F1.R * (rz(t[1]) * w) + arm.F1.p;
  if (std::hypot(u.x(), u.y()) < 1e-12 * arm.size) {
    t[0] = 0.0;  // on axis 1: q1 free
    out.singular = true;
  } else {
    t[0] = std::atan2(red.pp.y(), red.pp.x()) - std::atan2(u.y(), u.x());
  }
  // Newton's method on the forward model (the roots above carry the eigenvalues' rounding).
  for (int it = 0; it < 12; ++it) {
    const Eigen::Vector3d e = p - position(arm, t);
    if (e.norm() <= 1e-15 * arm.size) break;
    const Eigen::Matrix3d J = jacobian(arm, t);
    const Eigen::Vector3d dt = J.colPivHouseholderQr().solve(e);
    if (!dt.allFinite()) break;
    for (int i = 0; i < 3; ++i) t[i] += dt(i);
  }
  return {t[0], t[1], t[2]};
}

// The candidates as joints (wrapped, each once within 1e-7), kept when chain.fk reaches p, labelled
// by the sign of det J.
void keep_reaching(const Arm3R& arm, const Chain& chain, const Eigen::Vector3d& p, const JointLimits& limits,
                   const std::vector<std::array<double, 3>>& cand, ClosedFormSolutions& out) {
  std::vector<std::array<double, 3>> kept;
  for (auto& t : cand) {
    double q[3];
    for (int i = 0; i < 3; ++i) q[i] = wrap_angle(t[i] * arm.scale[i]);
    bool dup = false;
    for (auto& k : kept) dup = dup || near_angles(k.data(), q, 3, 1e-7);
    if (dup) continue;
    Rigid F;
    chain.fk(q, F);
    if (!((F.p - p).norm() <= 1e-9 * arm.size)) continue;
    kept.push_back({q[0], q[1], q[2]});
    const double d = det_3r(arm, q[1], q[2]);
    const bool sing = std::abs(d) <= 1e-9 * arm.size * arm.size * arm.size;
    out.singular = out.singular || sing;
    const bool within = fit_limits(q, 3, limits);
    out.add(q, sing ? "singular" : (d > 0 ? "det J > 0" : "det J < 0"), within);
  }
}

}  // namespace

ClosedFormSolutions ik_general_3r(const Arm3R& arm, const Chain& chain, const Eigen::Vector3d& p, const JointLimits& limits) {
  ClosedFormSolutions out;
  out.dof = 3;
  const Reduced3R red(arm, p);
  std::vector<std::array<double, 3>> cand;
  for (double t3 : roots_t3(red, out)) {
    double C1, C2;
    Eigen::Vector3d w;
    red.eqs(t3, C1, C2, w);
    const double rw = std::hypot(w.x(), w.y());
    std::vector<Eigen::Vector2d> Vs;
    red.v_candidates(C1, C2, rw, Vs);
    for (const Eigen::Vector2d& V : Vs) cand.push_back(solve_t2_t1(red, p, t3, w, rw, V, out));
  }
  keep_reaching(arm, chain, p, limits, cand, out);
  return out;
}

}  // namespace robokin
