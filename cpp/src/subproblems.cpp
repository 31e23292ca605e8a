// The Paden-Kahan subproblems, each reduced to a cos theta + b sin theta = c, or to one atan2.
#include "robokin/subproblems.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace robokin {
namespace {

// theta with a cos theta + b sin theta = c: atan2(b, a) -+ acos(c / |(a, b)|). `scale` is the size
// of the terms the coefficients were made from (the margin's unit).
SubproblemAngles sinusoid(double a, double b, double c, double scale) {
  SubproblemAngles out;
  const double r = std::hypot(a, b);
  const double eps = kSubproblemEps * std::max(scale, 1e-300);
  if (!(r > eps)) {  // no dependence on theta: every angle or none
    if (std::abs(c) <= eps) out.count = 1, out.singular = true;
    return out;
  }
  const double ratio = c / r;
  if (!(std::abs(ratio) <= 1.0 + kSubproblemEps)) return out;  // also NaN
  const double base = std::atan2(b, a);
  // Within the margin of +-1 the two solutions (nearly) coincide: flagged singular, and kept apart
  // unless their spread is 0 (the margin's roots are ~1e-6 apart: each is needed where a pose near
  // the singularity has both, its neighbours following them).
  out.singular = std::abs(ratio) >= 1.0 - kSubproblemEps;
  const double spread = std::acos(std::clamp(ratio, -1.0, 1.0));
  if (spread == 0.0 || spread == M_PI) {
    out.count = 1;
    out.theta[0] = base + spread;
    return out;
  }
  out.count = 2;
  out.theta[0] = base - spread, out.theta[1] = base + spread;
  return out;
}

}  // namespace

Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& k, double theta) {
  return Eigen::AngleAxisd(theta, k).toRotationMatrix();
}

SubproblemAngles subproblem1(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  SubproblemAngles out;
  const Eigen::Vector3d pp = p - k.dot(p) * k, qq = q - k.dot(q) * k;
  const double eps = kSubproblemEps * std::max(std::max(p.norm(), q.norm()), 1e-300);
  out.count = 1;
  if (pp.norm() <= eps) {
    out.singular = true;
    return out;
  }
  out.theta[0] = std::atan2(k.dot(pp.cross(qq)), pp.dot(qq));
  return out;
}

SubproblemAngles subproblem4(const Eigen::Vector3d& h, const Eigen::Vector3d& k, const Eigen::Vector3d& p, double d) {
  // h . R p = (k.p)(h.k) + cos theta h.(p - (k.p) k) + sin theta h.(k x p).
  const double kp = k.dot(p);
  return sinusoid(h.dot(p - kp * k), h.dot(k.cross(p)), d - kp * h.dot(k), h.norm() * p.norm() + std::abs(d));
}

SubproblemAngles subproblem3(const Eigen::Vector3d& k, const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d) {
  // |R p - q|^2 = |p|^2 + |q|^2 - 2 q . R p.
  return subproblem4(q, k, p, 0.5 * (p.squaredNorm() + q.squaredNorm() - d * d));
}

void subproblem2(const Eigen::Vector3d& k1, const Eigen::Vector3d& k2, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& q, SubproblemAngles& t1, SubproblemAngles& t2) {
  t1 = SubproblemAngles{}, t2 = SubproblemAngles{};
  // k2 . R(k1, -theta1) q = k2 . p: subproblem 4 in -theta1; then theta2 by subproblem 1.
  const SubproblemAngles a = subproblem4(k2, k1, q, k2.dot(p));
  for (int i = 0; i < a.count; ++i) {
    const double theta1 = -a.theta[i];
    const SubproblemAngles b = subproblem1(k2, p, axis_rotation(k1, -theta1) * q);
    t1.theta[t1.count++] = theta1;
    t2.theta[t2.count++] = b.theta[0];
    t1.singular = t1.singular || a.singular;
    t2.singular = t2.singular || b.singular;
  }
}

}  // namespace robokin
