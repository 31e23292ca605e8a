// The Paden-Kahan subproblems, each reduced to a cos theta + b sin theta = c, or to one angle
// between two vectors: cosines and sines by algebra, no trigonometric call.
#include "robokin/subproblems.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace robokin {
namespace {

// (x, y) / |(x, y)| and |(x, y)| (the unit turn and 0 when both are 0). One square root and one
// division (glibc's hypot costs several square roots), with hypot's care (no overflow or underflow
// of the squares) only where the squares leave the normal range.
Turn direction(double x, double y, double& length) {
  const double n2 = x * x + y * y;
  double inv;
  if (n2 > 1e-290 && n2 < 1e290) {
    length = std::sqrt(n2), inv = 1.0 / length;
  } else {
    length = std::hypot(x, y);
    if (!(length > 0.0)) return {};
    inv = 1.0 / length;
  }
  return {x * inv, y * inv};
}

// sqrt(a2 b2) of two squared lengths: one square root where their product is a normal float, two
// where it is not (lengths beyond ~1e77 or below ~1e-77, whose fourth powers leave the range).
double root_of_product(double a2, double b2) {
  const double product = a2 * b2;
  if (product >= std::numeric_limits<double>::min() && product <= std::numeric_limits<double>::max())
    return std::sqrt(product);
  return std::sqrt(a2) * std::sqrt(b2);
}

// theta with a cos theta + b sin theta = c: theta = beta -+ spread, beta the direction of (a, b) and
// cos spread = c / |(a, b)|. `scale` is the size of the terms the coefficients were made from (the
// margin's unit).
SubproblemAngles sinusoid(double a, double b, double c, double scale) {
  SubproblemAngles out;
  double r;
  const Turn beta = direction(a, b, r);
  const double eps = kSubproblemEps * std::max(scale, 1e-300);
  if (!(r > eps)) {  // no dependence on theta: every angle or none
    if (std::abs(c) <= eps) out.count = 1, out.singular = true;
    return out;
  }
  const double ratio = c / r;
  if (!(std::abs(ratio) <= 1.0 + kSubproblemEps)) return out;  // also NaN
  // Within the margin of +-1 the two solutions (nearly) coincide: flagged singular, and kept apart
  // unless their spread is 0 (the margin's roots are ~1e-6 apart: each is needed where a pose near
  // the singularity has both, its neighbours following them).
  out.singular = std::abs(ratio) >= 1.0 - kSubproblemEps;
  const double cs = std::clamp(ratio, -1.0, 1.0), sn = std::sqrt((1.0 - cs) * (1.0 + cs));  // of the spread
  const double ca = beta.c, sa = beta.s;
  if (sn == 0.0) {  // spread 0 or pi: one solution
    out.count = 1;
    out.turn[0] = {ca * cs, sa * cs};
    return out;
  }
  out.count = 2;
  out.turn[0] = {ca * cs + sa * sn, sa * cs - ca * sn};  // beta - spread
  out.turn[1] = {ca * cs - sa * sn, sa * cs + ca * sn};  // beta + spread
  return out;
}

}  // namespace

Turn direction(double x, double y) {
  double length;
  return direction(x, y, length);
}

SubproblemAngles subproblem1(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  SubproblemAngles out;
  const Eigen::Vector3d pp = p - k.dot(p) * k, qq = q - k.dot(q) * k;
  // |pp| <= kSubproblemEps max(|p|, |q|), in squares.
  const double eps2 = kSubproblemEps * kSubproblemEps * std::max(p.squaredNorm(), q.squaredNorm());
  out.count = 1;
  if (pp.squaredNorm() <= eps2) {
    out.singular = true;
    return out;
  }
  // The angle from pp to qq about k: (cos, sin) proportional to (pp . qq, k . pp x qq).
  out.turn[0] = direction(pp.dot(qq), k.dot(pp.cross(qq)));
  return out;
}

SubproblemAngles subproblem4(const Eigen::Vector3d& h, const Eigen::Vector3d& k, const Eigen::Vector3d& p, double d) {
  // h . R p = (k.p)(h.k) + cos theta h.(p - (k.p) k) + sin theta h.(k x p).
  const double kp = k.dot(p);
  return sinusoid(h.dot(p - kp * k), h.dot(k.cross(p)), d - kp * h.dot(k),
                  root_of_product(h.squaredNorm(), p.squaredNorm()) + std::abs(d));
}

SubproblemAngles subproblem3(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d) {
  // |R p - q|^2 = |p|^2 + |q|^2 - 2 q . R p.
  return subproblem4(q, k, p, 0.5 * (p.squaredNorm() + q.squaredNorm() - d * d));
}

Subproblem2::Subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p)
    : k1_(k1), k2_(k2), k2xk1_(k2.cross(k1)), pp_(p - k2.dot(p) * k2), w_(k2.cross(pp_)), k2k1_(k2.dot(k1)),
      k2p_(k2.dot(p)), k2sq_(k2.squaredNorm()), p2_(p.squaredNorm()), pp2_(pp_.squaredNorm()) {}

void Subproblem2::solve(const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2) const {
  t1 = SubproblemAngles{}, t2 = SubproblemAngles{};
  // k2 . R(k1, -theta1) q = k2 . p: subproblem 4 in -theta1 (h = k2, k = k1, p = q, d = k2 . p).
  const double q2 = q.squaredNorm(), kq = k1_.dot(q);
  const SubproblemAngles a = sinusoid(k2_.dot(q) - kq * k2k1_, q.dot(k2xk1_), k2p_ - kq * k2k1_,
                                      root_of_product(k2sq_, q2) + std::abs(k2p_));
  // theta2 turns p onto v = R(k1, -theta1) q about k2 (subproblem 1): its cosine and sine are
  // proportional to pp . v and (k2 x pp) . v.
  const bool on_axis = pp2_ <= kSubproblemEps * kSubproblemEps * std::max(p2_, q2);
  for (int i = 0; i < a.count; ++i) {
    const Eigen::Vector3d v = rotate(k1_, a.turn[i], q);
    t1.turn[t1.count++] = -a.turn[i];
    t2.turn[t2.count++] = on_axis ? Turn{} : direction(pp_.dot(v), w_.dot(v));
  }
  t1.singular = a.count > 0 && a.singular;
  t2.singular = a.count > 0 && on_axis;
}

void subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2) {
  Subproblem2(k1, k2, p).solve(q, t1, t2);
}

}  // namespace robokin
