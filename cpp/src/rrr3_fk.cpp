// 3-RRR forward model: every assembly mode of the actuated angles.
//
// With the elbows A_i known, leg i closes when |E + c_i(phi)|^2 = l2^2, c_i = R(phi) b_i - A_i.
// Subtracting leg 0's equation from legs 1 and 2 leaves a linear system M(phi) E = r(phi), solved
// by Cramer's rule E = N / D (D = det M, N = adj(M) r). Leg 0's equation times D^2,
//   F(phi) = |N + D c_0|^2 - D^2 l2^2,
// has no poles and is a trigonometric polynomial of degree 6 in phi (c_i, M are of degree 1,
// D and N of degree 2). Its 13 coefficients come exactly from 16 samples (a DFT); a fine scan of
// the polynomial (1 deg steps) is then searched interval by interval without any condition on
// neighbouring samples: an interval with a sign change holds one root when F' keeps its sign
// (certified by a bound on the third derivative), else it is bisected; an interval without one is
// certified free of roots by a bound on F'' (linear interpolation error), or its minimum of |F| is
// refined (a pair of close roots or a double root), or it is bisected. Each root phi is polished
// by Newton on the three loop equations from E = N / D and, where D is nearly 0 (two assembly
// modes at nearly the same phi, N / D = 0 / 0), from both points where the line M E = r cuts
// leg 0's circle; a pose is kept only if it closes the loops to 1e-10 m (1e-10 of R_b + R_e + l1 + l2
// for a robot larger than that), and only once: near a double root (det A = 0) Newton's end points
// scatter along the singular direction, and copies are told from distinct modes by the loops
// between them (same() below).
#include "robokin/rrr3.hpp"
#include "robokin/angles.hpp"

#include "kernel/isa.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace robokin {
namespace {

constexpr int kDegree = 6;
constexpr int kFit = 16;    // samples for the exact coefficients (> 2 * kDegree + 1)
constexpr int kScan = 360;  // scan step 1 deg; close pairs of roots are caught by search()

struct TrigPoly {
  double a[kDegree + 1];  // F = a_0 + sum_k a_k cos(k phi) + b_k sin(k phi)
  double b[kDegree + 1];

  // F, F' and F'' at phi (angle addition instead of 2 k transcendental calls).
  void eval(double phi, double& f, double& df, double& ddf) const {
    const double c1 = std::cos(phi), s1 = std::sin(phi);
    double c = 1, s = 0;
    f = a[0];
    df = ddf = 0;
    for (int k = 1; k <= kDegree; ++k) {
      const double cn = c * c1 - s * s1, sn = s * c1 + c * s1;
      c = cn, s = sn;
      f += a[k] * c + b[k] * s;
      df += k * (b[k] * c - a[k] * s);
      ddf -= k * k * (a[k] * c + b[k] * s);
    }
  }
  double value(double phi) const {
    double f, df, ddf;
    eval(phi, f, df, ddf);
    return f;
  }
};

struct Tables {
  double fit_phi[kFit], fit_cos[kFit][kDegree + 1], fit_sin[kFit][kDegree + 1];
  double fit_c[kFit], fit_s[kFit];  // std::cos, std::sin of fit_phi (what Elimination::F takes)
  // scan_cos[k][j] = cos(k scan_phi[j]): k-major, so that the scan's loop over j vectorises.
  double scan_phi[kScan + 1], scan_cos[kDegree + 1][kScan], scan_sin[kDegree + 1][kScan];
  double scan_h[kScan];  // scan_phi[j + 1] - scan_phi[j], the intervals' widths as search() takes them
  Tables() {
    for (int j = 0; j < kFit; ++j) {
      fit_phi[j] = -M_PI + 2 * M_PI * j / kFit;
      for (int k = 0; k <= kDegree; ++k) fit_cos[j][k] = std::cos(k * fit_phi[j]), fit_sin[j][k] = std::sin(k * fit_phi[j]);
      fit_c[j] = std::cos(fit_phi[j]), fit_s[j] = std::sin(fit_phi[j]);
    }
    for (int j = 0; j <= kScan; ++j) scan_phi[j] = -M_PI + 2 * M_PI * j / kScan;
    for (int j = 0; j < kScan; ++j) scan_h[j] = scan_phi[j + 1] - scan_phi[j];
    for (int j = 0; j < kScan; ++j)
      for (int k = 0; k <= kDegree; ++k)
        scan_cos[k][j] = std::cos(k * scan_phi[j]), scan_sin[k][j] = std::sin(k * scan_phi[j]);
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// The elimination at one phi: E = N / D and the residual F.
struct Elimination {
  const Eigen::Matrix<double, 3, 2>& A;
  const Eigen::Vector2d* b;  // platform joints in the effector frame
  double l2;

  struct Detail {
    Eigen::Vector2d N, c0, r;
    Eigen::Matrix2d M;
    double D;
  };

  double F(double phi, Detail* detail = nullptr) const { return F(std::cos(phi), std::sin(phi), detail); }
  // F from cos phi and sin phi.
  double F(double c, double s, Detail* detail = nullptr) const {
    Eigen::Vector2d ci[3];
    for (int i = 0; i < 3; ++i)
      ci[i] = Eigen::Vector2d(c * b[i].x() - s * b[i].y(), s * b[i].x() + c * b[i].y()) - A.row(i).transpose();
    Eigen::Matrix2d M;
    M.row(0) = 2 * (ci[1] - ci[0]).transpose();
    M.row(1) = 2 * (ci[2] - ci[0]).transpose();
    const Eigen::Vector2d r(ci[0].squaredNorm() - ci[1].squaredNorm(), ci[0].squaredNorm() - ci[2].squaredNorm());
    const double det = M.determinant();
    const Eigen::Vector2d n(M(1, 1) * r(0) - M(0, 1) * r(1), -M(1, 0) * r(0) + M(0, 0) * r(1));
    if (detail) *detail = Detail{n, ci[0], r, M, det};
    return (n + det * ci[0]).squaredNorm() - det * det * l2 * l2;
  }
};

// A root of p in [lo, hi] where p(lo) = flo and p(hi) have opposite signs: Newton kept inside the
// bracket.
double refine(const TrigPoly& p, double lo, double hi, double flo) {
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 100 && hi - lo > 1e-15; ++it) {
    double f, df, ddf;
    p.eval(x, f, df, ddf);
    if (f == 0) return x;
    if ((f < 0) == (flo < 0)) lo = x, flo = f;
    else hi = x;
    const double nx = df != 0 ? x - f / df : 0.5 * (lo + hi);
    if (!(nx > lo && nx < hi)) {
      x = 0.5 * (lo + hi);
    } else {
      if (std::abs(nx - x) < 1e-16) return nx;
      x = nx;
    }
  }
  return x;
}

// The extremum of p in [lo, hi] where p'(lo), p'(hi) have opposite signs.
double extremum(const TrigPoly& p, double lo, double hi) {
  TrigPoly d;  // p' as a trigonometric polynomial
  d.a[0] = d.b[0] = 0;
  for (int k = 1; k <= kDegree; ++k) d.a[k] = k * p.b[k], d.b[k] = -k * p.a[k];
  return refine(d, lo, hi, d.value(lo));
}


// Roots of p in [lo, hi] where p(lo) = flo and p(hi) = fhi are non-zero with the same sign.
void search(const TrigPoly& p, double curvature, double jerk, double lo, double hi, double flo, double fhi, int depth,
            std::vector<double>& roots);

// Roots of p in [lo, hi] where p(lo) = flo and p(hi) = fhi are non-zero with opposite signs: one
// root when p' keeps its sign (certified by |p'| >= min(|p'(lo)|, |p'(hi)|) - max|p^(3)| h^2 / 8),
// else the interval is bisected (three roots may hide in it).
void search_change(const TrigPoly& p, double curvature, double jerk, double lo, double hi, double flo, double fhi,
                   int depth, std::vector<double>& roots) {
  const double h = hi - lo;
  double f, dlo, dhi, dd;
  p.eval(lo, f, dlo, dd);
  p.eval(hi, f, dhi, dd);
  if (depth == 0 || ((dlo < 0) == (dhi < 0) && std::min(std::abs(dlo), std::abs(dhi)) > jerk * h * h / 8)) {
    roots.push_back(refine(p, lo, hi, flo));
    return;
  }
  const double mid = 0.5 * (lo + hi), fmid = p.value(mid);
  if (fmid == 0) {
    roots.push_back(mid);
    return;
  }
  for (int half = 0; half < 2; ++half) {
    const double a = half ? mid : lo, b = half ? hi : mid, fa = half ? fmid : flo, fb = half ? fhi : fmid;
    if ((fa < 0) != (fb < 0)) search_change(p, curvature, jerk, a, b, fa, fb, depth - 1, roots);
    else search(p, curvature, jerk, a, b, fa, fb, depth - 1, roots);
  }
}

void search(const TrigPoly& p, double curvature, double jerk, double lo, double hi, double flo, double fhi, int depth,
            std::vector<double>& roots) {
  const double h = hi - lo;
  if (std::min(std::abs(flo), std::abs(fhi)) > curvature * h * h / 8) return;  // certified: no root
  double f, dlo, dhi, dd;
  p.eval(lo, f, dlo, dd);
  p.eval(hi, f, dhi, dd);
  const double sign = flo < 0 ? -1.0 : 1.0;
  if (sign * dlo < 0 && sign * dhi > 0) {
    // |F| falls then rises: its minimum decides between no root, a double root and a pair.
    const double m = extremum(p, lo, hi);
    const double fm = p.value(m);
    if (fm == 0 || std::abs(fm) < 1e-13) {
      roots.push_back(m);  // a double root (tangency): the closure test in fk_all decides
      // p' may have had other roots in [lo, hi] (another tangency nearby): search on either side.
      if (fm == 0 || depth == 0) return;
      for (int half = 0; half < 2; ++half) {
        const double a = half ? m : lo, b = half ? hi : m, fa = half ? fm : flo, fb = half ? fhi : fm;
        if ((fa < 0) != (fb < 0)) search_change(p, curvature, jerk, a, b, fa, fb, depth - 1, roots);
        else search(p, curvature, jerk, a, b, fa, fb, depth - 1, roots);
      }
      return;
    }
    if ((fm < 0) != (flo < 0)) {
      search_change(p, curvature, jerk, lo, m, flo, fm, depth, roots);
      search_change(p, curvature, jerk, m, hi, fm, fhi, depth, roots);
      return;
    }
    // F'(m) = 0, so |F(x) - F(m)| <= max|F''| (x - m)^2 / 2: no root in [lo, hi] when |F(m)| beats that
    // (whatever other extrema the interval holds).
    const double reach = std::max(m - lo, hi - m);
    if (std::abs(fm) > curvature * reach * reach / 2) return;
  }
  if (depth == 0) return;
  const double mid = 0.5 * (lo + hi), fmid = p.value(mid);
  if (fmid == 0) {
    roots.push_back(mid);
  } else if ((fmid < 0) != (flo < 0)) {
    search_change(p, curvature, jerk, lo, mid, flo, fmid, depth - 1, roots);
    search_change(p, curvature, jerk, mid, hi, fmid, fhi, depth - 1, roots);
  } else {
    search(p, curvature, jerk, lo, mid, flo, fmid, depth - 1, roots);
    search(p, curvature, jerk, mid, hi, fmid, fhi, depth - 1, roots);
  }
}
// F on the scan, f[kScan] = f[0] (the wrap): the same sums as term by term at each phi, term k
// over every phi at once (a loop the vectoriser takes; run by kernel::run_for_isa: the same bits in
// every build).
struct Scan {
  static ROBOKIN_KERNEL void run(const TrigPoly* p, const Tables* t, double* __restrict f) {
    for (int j = 0; j < kScan; ++j) f[j] = p->a[0];
    for (int k = 1; k <= kDegree; ++k) {
      const double ak = p->a[k], bk = p->b[k];
      const double* __restrict c = t->scan_cos[k];
      const double* __restrict sn = t->scan_sin[k];
      for (int j = 0; j < kScan; ++j) f[j] += ak * c[j] + bk * sn[j];
    }
    f[kScan] = f[0];
  }
};

// quiet[j]: interval j has no zero at its ends, no sign change and min(|F(lo)|, |F(hi)|) >
// max|F''| h^2 / 8, the test search() starts with (the same expression: the same decision), for
// every interval in one branch-free loop (run as Scan).
struct QuietIntervals {
  static ROBOKIN_KERNEL void run(const double* __restrict f, const double* __restrict h, double curvature,
                                 unsigned char* __restrict quiet) {
    for (int j = 0; j < kScan; ++j) {
      const double lo = f[j], hi = f[j + 1];
      const bool same = (lo < 0) == (hi < 0);
      const bool nonzero = (lo != 0) & (hi != 0);
      const bool certified = std::min(std::abs(lo), std::abs(hi)) > curvature * h[j] * h[j] / 8;
      quiet[j] = same & nonzero & certified;
    }
  }
};

// F's exact coefficients from kFit samples, divided by the largest; false when F vanishes or
// overflows (no assembly mode is found then).
bool fit_trig_poly(const Elimination& elim, const Tables& t, TrigPoly& p) {
  double samples[kFit];
  for (int j = 0; j < kFit; ++j) samples[j] = elim.F(t.fit_c[j], t.fit_s[j]);
  double scale = 0;
  for (int k = 0; k <= kDegree; ++k) {
    double sa = 0, sb = 0;
    for (int j = 0; j < kFit; ++j) sa += samples[j] * t.fit_cos[j][k], sb += samples[j] * t.fit_sin[j][k];
    p.a[k] = (k == 0 ? 1.0 : 2.0) * sa / kFit;
    p.b[k] = k == 0 ? 0.0 : 2.0 * sb / kFit;
    scale = std::max({scale, std::abs(p.a[k]), std::abs(p.b[k])});
  }
  if (!(scale > 0) || !std::isfinite(scale)) return false;
  for (int k = 0; k <= kDegree; ++k) p.a[k] /= scale, p.b[k] /= scale;
  return true;
}

// Every root phi of F in [-pi, pi), two roots closer than a scan step included.
std::vector<double> roots_of(const TrigPoly& p, const Tables& t) {
  double f[kScan + 1];
  kernel::run_for_isa<Scan>(&p, &t, f);

  // Every interval of the scan either has a sign change (one root, refined), or is certified free
  // of roots by |F| >= min(|F(lo)|, |F(hi)|) - max|F''| h^2 / 8 (the error bound of linear
  // interpolation), or is searched: a minimum of |F| inside (F' turns towards zero then away from
  // it) is refined and checked for a pair of roots or a double root; otherwise it is bisected.
  // No condition on neighbouring samples: two roots closer than a scan step are found wherever
  // they fall (issue: 5 of 24,000 near-singular assemblies were missed by the former dip test).
  double curvature = 0, jerk = 0;  // max |F''| and max |F'''| over phi
  for (int k = 1; k <= kDegree; ++k) {
    curvature += k * k * std::hypot(p.a[k], p.b[k]);
    jerk += k * k * k * std::hypot(p.a[k], p.b[k]);
  }
  unsigned char quiet[kScan];
  kernel::run_for_isa<QuietIntervals>(f, t.scan_h, curvature, quiet);
  std::vector<double> roots;
  roots.reserve(2 * kDegree);  // F has at most 2 * kDegree roots
  for (int j = 0; j < kScan; ++j) {
    if (quiet[j]) continue;  // what search() would certify at once
    const int next = (j + 1) % kScan;
    const double lo = t.scan_phi[j], hi = t.scan_phi[j + 1];  // hi = pi for the last interval
    if (f[j] == 0) {
      roots.push_back(lo);
    } else if ((f[j] < 0) != (f[next] < 0) && f[next] != 0) {
      search_change(p, curvature, jerk, lo, hi, f[j], f[next], 8, roots);
    } else if (f[next] != 0) {
      search(p, curvature, jerk, lo, hi, f[j], f[next], 8, roots);
    }
  }
  return roots;
}

}  // namespace

// Two poses (within 1e-3) are one assembly mode when the loops close between them as well as at
// the worse end, up to rounding: between two distinct modes d apart they open by ~ k d^2 / 4 (the
// equations are quadratic), while at a double root (det A = 0), where the loops close to 1e-13 m
// anywhere within some sqrt(1e-13 m / k) and Newton stops there, they stay closed. No fixed
// distance tells the two cases apart. "Between" is the midpoint moved onto the valley of
// near-solutions (it curves: a chord of 1e-5 leaves it by more than the error) by a Newton step
// without its least-determined direction (phi scaled by R_e, its lever).
bool RRR3::same_mode(const Eigen::Matrix<double, 3, 2>& A, const Pose& p, double ep, const Pose& q, double eq) const {
  const double size = rb_ + re_ + l1_ + l2_;
  const double eps = std::numeric_limits<double>::epsilon();
  const double dphi = wrap_angle(q(2) - p(2));
  if ((p.head<2>() - q.head<2>()).norm() > 1e-3 * size || std::abs(dphi) > 1e-3) return false;
  Pose mid(0.5 * (p(0) + q(0)), 0.5 * (p(1) + q(1)), p(2) + 0.5 * dphi);
  Eigen::Vector3d f;
  Eigen::Matrix3d J;
  loops(A, mid, f, J);
  J.col(2) /= re_;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  for (int k = 0; k < 2; ++k) {
    const double sv = svd.singularValues()(k);
    if (sv > 0) step += svd.matrixV().col(k) * (svd.matrixU().col(k).dot(f) / sv);
  }
  step(2) /= re_;
  mid -= step;
  return loops(A, mid, f, J) <= std::max(ep, eq) + 2 * eps * size;
}

std::vector<Pose> RRR3::fk_all(const Eigen::Vector3d& alpha) const {
  const Tables& t = tables();
  const Eigen::Matrix<double, 3, 2> A = elbows(alpha);
  const Elimination elim{A, b_.data(), l2_};
  TrigPoly p;
  std::vector<Pose> out;
  if (!fit_trig_poly(elim, t, p)) return out;
  const std::vector<double> roots = roots_of(p, t);

  // Each root phi gives E = N / D. Where D = det M is (nearly) zero, c_0, c_1, c_2 are (nearly)
  // collinear: M E = r only fixes a line, which leg 0's circle cuts in two points, possibly two
  // assembly modes at (nearly) the same phi (then F has a double root and N / D is 0 / 0). Both
  // intersections are tried as well there.
  const double size = rb_ + re_ + l1_ + l2_;
  // 1e-10 m, relative for robots larger than 1 m (rounding alone reaches some 1e-16 of the size).
  const double close = 1e-10 * std::max(1.0, size);
  const double eps = std::numeric_limits<double>::epsilon();
  out.reserve(2 * kDegree);
  std::vector<double> error;  // closure error of each pose in out
  error.reserve(2 * kDegree);
  auto add = [&](const Pose& guess, double phi) {
    if (!guess.allFinite()) return;
    RRR3Fk polished = close_loops(A, guess, {8, 1e-13});
    if (!(polished.error < close)) return;
    // Closed to rounding where Newton gets there and stays on the same root (at a double root it
    // converges only linearly and may jump once at rounding level): two distinct modes close
    // together then close much better than the loops between them, which same_mode needs to see.
    // A move within 1e-12 of the size (a simple root's last steps) stays on it: between two poses
    // that close and lie that near, the loops open by some 1e-24 of the size, far below rounding,
    // so same_mode would take them as one.
    const RRR3Fk finer = close_loops(A, polished.pose, {8, 4 * eps * size});
    const bool stays = (finer.pose.head<2>() - polished.pose.head<2>()).norm() <= 1e-12 * size &&
                       std::abs(wrap_angle(finer.pose(2) - polished.pose(2))) <= 1e-12;
    if (finer.error < polished.error &&
        (stays || same_mode(A, polished.pose, polished.error, finer.pose, finer.error)))
      polished = finer;
    // Slid far to another root: that one is polished from its own phi. Near a double root the two
    // assembly modes may lie some 1e-5 rad on either side of the phi found.
    if (std::abs(wrap_angle(polished.pose(2) - phi)) > 1e-3) return;
    Pose q = polished.pose;
    q(2) = wrap_angle(q(2));
    if (q(2) >= M_PI) q(2) -= 2 * M_PI;
    for (std::size_t k = 0; k < out.size(); ++k)
      if (same_mode(A, out[k], error[k], q, polished.error)) {  // found again: keep the copy closing best
        if (polished.error < error[k]) out[k] = q, error[k] = polished.error;
        return;
      }
    out.push_back(q);
    error.push_back(polished.error);
  };
  for (double phi : roots) {
    Elimination::Detail d;
    elim.F(phi, &d);
    add(Pose(d.N.x() / d.D, d.N.y() / d.D, phi), phi);
    if (!(std::abs(d.D) < 1e-3 * d.M.squaredNorm())) continue;
    const int k = d.M.row(0).squaredNorm() >= d.M.row(1).squaredNorm() ? 0 : 1;
    const Eigen::Vector2d g = d.M.row(k).transpose();
    if (!(g.squaredNorm() > 0)) continue;
    const Eigen::Vector2d e0 = g * (d.r(k) / g.squaredNorm()), n = Eigen::Vector2d(-g.y(), g.x()).normalized();
    const Eigen::Vector2d w = e0 + d.c0;  // |e0 + t n + c_0| = l2
    const double bq = n.dot(w), disc = std::max(0.0, bq * bq - (w.squaredNorm() - l2_ * l2_));
    for (double sign : {-1.0, 1.0}) {
      const Eigen::Vector2d e = e0 + (-bq + sign * std::sqrt(disc)) * n;
      add(Pose(e.x(), e.y(), phi), phi);
    }
  }
  std::sort(out.begin(), out.end(), [](const Pose& a, const Pose& b) { return a(2) < b(2); });
  return out;
}

}  // namespace robokin
