// General 3R positioning arms: inverse solutions from a trigonometric polynomial in q3, aspects and
// cusp points of the singular curves.
#include "robokin/ik_3r.hpp"
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

constexpr double kPi = M_PI;

Rigid frame_of(const KDL::Frame& f) {
  Rigid r;
  for (int i = 0; i < 3; ++i) {
    r.p(i) = f.p(i);
    for (int j = 0; j < 3; ++j) r.R(i, j) = f.M(i, j);
  }
  return r;
}

Eigen::Matrix3d rz(double a) {
  Eigen::Matrix3d m;
  const double c = std::cos(a), s = std::sin(a);
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

// e_z x v
Eigen::Vector3d ez_cross(const Eigen::Vector3d& v) { return {-v.y(), v.x(), 0.0}; }

[[noreturn]] void not_3r(const std::string& why) { throw std::invalid_argument("chain: not a 3R arm (" + why + ")"); }

// Points and derivatives in the frame after joint 1's rotation, at DH-like angles t = s q.
struct Local {
  Eigen::Vector3d w, u, du2, du3;
};

Local local(const Arm3R& a, double t2, double t3) {
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

Eigen::Vector3d position(const Arm3R& a, const double t[3]) {
  return a.base.R * (rz(t[0]) * local(a, t[1], t[2]).u) + a.base.p;
}

Eigen::Matrix3d jacobian(const Arm3R& a, const double t[3]) {
  const Local L = local(a, t[1], t[2]);
  const Eigen::Matrix3d R = a.base.R * rz(t[0]);
  Eigen::Matrix3d J;
  J.col(0) = R * ez_cross(L.u);
  J.col(1) = R * L.du2;
  J.col(2) = R * L.du3;
  return J;
}

// det J at (0, t2, t3), angles t = s q: rho det D up to its sign, smooth everywhere (det D
// alone is not across axis 1).
double det_t(const Arm3R& a, double t2, double t3) {
  const double t[3] = {0.0, t2, t3};
  return jacobian(a, t).determinant();
}

// The image of the singular curve's tangent, D tau, at (t2, t3).
Eigen::Vector2d image_tangent(const Arm3R& a, double t2, double t3) {
  const double h = 1e-6;
  const double g2 = (det_t(a, t2 + h, t3) - det_t(a, t2 - h, t3)) / (2 * h);
  const double g3 = (det_t(a, t2, t3 + h) - det_t(a, t2, t3 - h)) / (2 * h);
  const Local L = local(a, t2, t3);
  const double rho = std::hypot(L.u.x(), L.u.y());
  Eigen::Matrix2d D;
  D << (L.u.x() * L.du2.x() + L.u.y() * L.du2.y()) / rho, (L.u.x() * L.du3.x() + L.u.y() * L.du3.y()) / rho,
      L.du2.z(), L.du3.z();
  return D * Eigen::Vector2d(-g3, g2);
}

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
      since = since * frame_of(seg.pose(0.0));
      continue;
    }
    ++j;
    if (joint.getType() >= KDL::Joint::TransAxis) not_3r("joint " + std::to_string(j + 1) + " is prismatic");
    const Rigid P0 = frame_of(joint.pose(0.0)), P1 = frame_of(joint.pose(0.5));
    const bool plus = (P1.R - rz(0.5)).cwiseAbs().maxCoeff() < 1e-12;
    const bool minus = (P1.R - rz(-0.5)).cwiseAbs().maxCoeff() < 1e-12;
    if ((P0.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-12 || P0.p.norm() > 0 || P1.p.norm() > 0 ||
        !(plus || minus))
      not_3r("joint " + std::to_string(j + 1) + " does not turn about the z axis of its frame");
    arm.scale[j] = plus ? 1.0 : -1.0;
    if (j == 0) arm.base = since;
    else after[j - 1] = since;
    since = frame_of(seg.pose(0.0));
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

ClosedFormSolutions ik_3r(const Arm3R& arm, const Chain& chain, const Eigen::Vector3d& p, const JointLimits& limits) {
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

namespace {

// The torus grid of cuspidal_3r: angle(i) = -pi + (i + 0.37) 2 pi / N, i taken modulo N.
struct TorusGrid {
  int N;
  double step, off;
  explicit TorusGrid(int n) : N(n), step(2 * kPi / n), off(0.37 * step) {}
  double angle(int i) const { return -kPi + off + step * ((i % N + N) % N); }
};

// sign(det J) (joint variables) into res.sign, and det J at the angles t = s q (smooth across
// axis 1) into the returned grid, row = q2.
std::vector<double> sample_det(const Arm3R& arm, const TorusGrid& G, CuspidalResult& res) {
  const int N = G.N;
  res.sign.assign(static_cast<size_t>(N) * N, 0);
  std::vector<double> dd(static_cast<size_t>(N) * N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const double q2 = G.angle(i), q3 = G.angle(j);
      const double d = det_3r(arm, q2, q3);
      res.sign[i * N + j] = d > 0 ? 1 : (d < 0 ? -1 : 0);
      dd[i * N + j] = det_t(arm, arm.scale[1] * q2, arm.scale[2] * q3);
    }
  return dd;
}

// Whether the grid step from cell (i, j) by (di, dj) keeps det J of sign `sign` all along. Two cells
// of one sign may still be parted by two singular curves crossing between them (opposite quadrants
// of a crossing have the same sign): the step must keep it. Nor may det J touch 0 between them
// without changing sign (a double zero, as where the tool crosses axis 1 of an arm whose first two
// axes intersect): a dip of |det J| along the step is followed down to its minimum.
bool step_keeps_sign(const Arm3R& arm, const TorusGrid& G, int i, int j, int di, int dj, int sign) {
  const double step = G.step;
  const auto det_at_u = [&](double u) { return det_3r(arm, G.angle(i) + u * di * step, G.angle(j) + u * dj * step); };
  bool kept = true;
  double v[9];
  for (int m = 0; m <= 8 && kept; ++m) {
    v[m] = det_at_u(m / 8.0);
    kept = (v[m] > 0 ? 1 : (v[m] < 0 ? -1 : 0)) == sign;
  }
  for (int m = 1; m < 8 && kept; ++m) {
    if (!(std::abs(v[m]) <= std::abs(v[m - 1]) && std::abs(v[m]) <= std::abs(v[m + 1]) &&
          std::abs(v[m]) < 0.25 * std::min(std::abs(v[0]), std::abs(v[8]))))
      continue;
    double lo = (m - 1) / 8.0, hi = (m + 1) / 8.0;
    for (int it = 0; it < 60; ++it) {  // ternary search for the minimum of |det J|
      const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      if (std::abs(det_at_u(a)) < std::abs(det_at_u(b))) hi = b;
      else lo = a;
    }
    const double dmin = det_at_u(0.5 * (lo + hi));
    kept = (dmin > 0 ? 1 : (dmin < 0 ? -1 : 0)) == sign &&
           std::abs(dmin) > 1e-6 * std::min(std::abs(v[0]), std::abs(v[8]));
  }
  return kept;
}

// Aspects: the 4-connected components of one sign of det J on the torus (res.label, res.aspects),
// a step joining two cells only where det J keeps its sign along it.
void label_aspects(const Arm3R& arm, const TorusGrid& G, CuspidalResult& res) {
  const int N = G.N;
  std::vector<int> label(static_cast<size_t>(N) * N, -1);
  for (int s = 0; s < N * N; ++s) {
    if (label[s] >= 0 || res.sign[s] == 0) continue;
    std::vector<int> stack = {s};
    label[s] = res.aspects;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const int i = c / N, j = c % N;
      const int nb[4] = {((i + 1) % N) * N + j, ((i + N - 1) % N) * N + j, i * N + (j + 1) % N, i * N + (j + N - 1) % N};
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const int n = nb[k];
        if (label[n] >= 0 || res.sign[n] != res.sign[s]) continue;
        if (step_keeps_sign(arm, G, i, j, di[k], dj[k], res.sign[s])) label[n] = res.aspects, stack.push_back(n);
      }
    }
    ++res.aspects;
  }
  res.label = label;
}

// det D (as det J at t = s q) and its gradient by central differences, at x = (t2, t3).
double det_at(const Arm3R& arm, const Eigen::Vector2d& x) { return det_t(arm, x(0), x(1)); }

Eigen::Vector2d det_gradient(const Arm3R& arm, const Eigen::Vector2d& x, double h) {
  return Eigen::Vector2d((det_at(arm, x + Eigen::Vector2d(h, 0)) - det_at(arm, x - Eigen::Vector2d(h, 0))) / (2 * h),
                         (det_at(arm, x + Eigen::Vector2d(0, h)) - det_at(arm, x - Eigen::Vector2d(0, h))) / (2 * h));
}

// Distance of the workspace point of (t2, t3) from axis 1.
double rho_at(const Arm3R& arm, const Eigen::Vector2d& x) {
  const Local L = local(arm, x(0), x(1));
  return std::hypot(L.u.x(), L.u.y());
}

// The zero of det D on the edge a -> b (fa = det D at a, the other end of opposite sign), by
// bisection; false where det D is NaN or the point is on (near) axis 1, where the map to
// (rho, z) is not smooth and no cusp of the workspace is sought.
bool edge_crossing(const Arm3R& arm, Eigen::Vector2d a, Eigen::Vector2d b, double fa, Eigen::Vector2d& x) {
  for (int it = 0; it < 60; ++it) {
    const Eigen::Vector2d m = 0.5 * (a + b);
    const double fm = det_at(arm, m);
    if (std::isnan(fm)) return false;
    if ((fm > 0) == (fa > 0)) a = m, fa = fm;
    else b = m;
  }
  x = 0.5 * (a + b);
  // On (near) axis 1 the map to (rho, z) is not smooth: no cusp of the workspace is sought there.
  return rho_at(arm, x) > 1e-3 * arm.size;
}

// The crossings of det D = 0 with the edges of grid cell (i, j) (corners unwrapped, t = s q, so
// the cell is a square even across +-pi); none when a corner's det is not finite.
std::vector<Eigen::Vector2d> cell_crossings(const Arm3R& arm, const TorusGrid& G, const std::vector<double>& dd, int i,
                                            int j) {
  const int N = G.N;
  const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
  double v[4];
  Eigen::Vector2d corner[4];
  bool finite = true;
  for (int k = 0; k < 4; ++k) {
    v[k] = dd[(ci[k] % N) * N + cj[k] % N];
    // Unwrapped corner coordinates (t = s q), so the cell is a square even across +-pi.
    corner[k] = Eigen::Vector2d(arm.scale[1] * (-kPi + G.off + G.step * ci[k]), arm.scale[2] * (-kPi + G.off + G.step * cj[k]));
    finite = finite && std::isfinite(v[k]);
  }
  std::vector<Eigen::Vector2d> xs;
  if (!finite) return xs;
  for (int k = 0; k < 4; ++k) {
    const int l = (k + 1) % 4;
    if ((v[k] > 0) != (v[l] > 0)) {
      Eigen::Vector2d x;
      if (edge_crossing(arm, corner[k], corner[l], v[k], x)) xs.push_back(x);
    }
  }
  return xs;
}

// Between two crossings whose image tangents D tau point opposite ways (ta the first's): the point
// where D tau reverses, by bisection along the curve (each midpoint pulled back onto det D = 0 by
// Newton along its gradient); false when the pull-back fails.
bool reversal_between(const Arm3R& arm, Eigen::Vector2d a, Eigen::Vector2d b, const Eigen::Vector2d& ta,
                      Eigen::Vector2d& x) {
  x = a;
  for (int it = 0; it < 50; ++it) {
    x = 0.5 * (a + b);
    for (int k = 0; k < 4; ++k) {  // Newton onto det D = 0 along its gradient
      const double h = 1e-7, fx = det_at(arm, x);
      const Eigen::Vector2d gr = det_gradient(arm, x, h);
      if (!(gr.squaredNorm() > 0) || !std::isfinite(fx)) return false;
      x -= fx * gr / gr.squaredNorm();
    }
    const Eigen::Vector2d tx = image_tangent(arm, x(0), x(1));
    if (tx.dot(ta) > 0) a = x;
    else b = x;
  }
  return true;
}

// The cusp in grid cell (i, j), if any, into res.cusps (each once): a cell crossed once by
// det D = 0 (two sign changes on its edges) whose image tangents at the two crossings point
// opposite ways has a cusp in between.
void cusp_in_cell(const Arm3R& arm, const TorusGrid& G, const std::vector<double>& dd, int i, int j,
                  CuspidalResult& res) {
  const std::vector<Eigen::Vector2d> xs = cell_crossings(arm, G, dd, i, j);
  if (xs.size() != 2) return;
  Eigen::Vector2d ta = image_tangent(arm, xs[0](0), xs[0](1)), tb = image_tangent(arm, xs[1](0), xs[1](1));
  if (!(ta.dot(tb) < 0)) return;
  Eigen::Vector2d x;
  if (!reversal_between(arm, xs[0], xs[1], ta, x)) return;
  // Where two singular curves cross (det J factors, as for the arms of Pieper's conditions),
  // D tau also reverses, but there grad det D vanishes: not a cusp of a smooth curve.
  const auto grad_norm = [&](const Eigen::Vector2d& y) {
    const Eigen::Vector2d gr = det_gradient(arm, y, 1e-7);
    return std::hypot(gr(0), gr(1));
  };
  if (!(grad_norm(x) > 1e-2 * std::max(grad_norm(xs[0]), grad_norm(xs[1])))) return;
  // On axis 1 det D is not smooth (rho is not): no cusp point of the workspace there.
  if (rho_at(arm, x) < 1e-4 * arm.size) return;
  CuspPoint c;
  c.q2 = wrap_angle(x(0) * arm.scale[1]);
  c.q3 = wrap_angle(x(1) * arm.scale[2]);
  const Local L = local(arm, x(0), x(1));
  c.rho = std::hypot(L.u.x(), L.u.y());
  c.z = L.u.z();
  bool dup = false;
  for (const CuspPoint& o : res.cusps)
    dup = dup || (std::abs(wrap_angle(o.q2 - c.q2)) < 1e-5 && std::abs(wrap_angle(o.q3 - c.q3)) < 1e-5);
  if (!dup) res.cusps.push_back(c);
}

}  // namespace

CuspidalResult cuspidal_3r(const Arm3R& arm, int N) {
  CuspidalResult res;
  res.resolution = N;
  const TorusGrid G(N);
  res.grid.resize(N);
  for (int i = 0; i < N; ++i) res.grid[i] = G.angle(i);
  const std::vector<double> dd = sample_det(arm, G, res);
  label_aspects(arm, G, res);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) cusp_in_cell(arm, G, dd, i, j, res);
  res.cuspidal = !res.cusps.empty();
  return res;
}

}  // namespace robokin
