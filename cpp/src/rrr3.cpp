// 3-RRR: geometry, analytic and numerical inverse models, the seed's Jacobians, singularities.
#include "robokin/rrr3.hpp"
#include "robokin/angles.hpp"

#include "robokin/parallel.hpp"

#include "kernel/fast_math.hpp"
#include "kernel/rrr3_ik_batch.hpp"
#include "rrr3_leg.hpp"
#include "rrr3_pose_eval.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace robokin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Lengths between 1 um and 1000 km: the squares and cubes the models use (|OB|^2, l1^3, cell
// areas) then neither overflow nor underflow, and closure tolerances of 1e-10 of the size hold.
void check_length(double v, const char* name) {
  if (!(v >= 1e-6 && v <= 1e6))
    throw std::invalid_argument(std::string(name) + ": must be a length in [1e-6, 1e6] m, got " + number(v));
}

// closure_error for the elbows A: max_i | |B_i - A_i| - l2 | with B_i as platform_joint computes
// it (the same operations; cos and sin of phi once).
double closure_at(const Eigen::Matrix<double, 3, 2>& A, const Pose& pose, const std::array<Eigen::Vector2d, 3>& b,
                  double l2) {
  const double c = std::cos(pose(2)), s = std::sin(pose(2));
  double err = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d B(pose(0) + c * b[i].x() - s * b[i].y(), pose(1) + s * b[i].x() + c * b[i].y());
    err = std::max(err, std::abs((B - A.row(i).transpose()).norm() - l2));
  }
  return err;
}

}  // namespace

RRR3::RRR3(double base_radius, double platform_radius, double l1, double l2)
    : rb_(base_radius), re_(platform_radius), l1_(l1), l2_(l2) {
  check_length(base_radius, "base_radius");
  check_length(platform_radius, "platform_radius");
  check_length(l1, "l1");
  check_length(l2, "l2");
  for (int i = 0; i < 3; ++i) {
    const double t = -M_PI / 2 + 2 * M_PI / 3 * i;
    o_[i] = rb_ * Eigen::Vector2d(std::cos(t), std::sin(t));
    b_[i] = re_ * Eigen::Vector2d(std::cos(t), std::sin(t));
  }
}

Mode RRR3::mode_at(int k) {
  return {(k & 4) ? -1 : 1, (k & 2) ? -1 : 1, (k & 1) ? -1 : 1};
}

Eigen::Vector2d RRR3::platform_joint(const Pose& pose, int i) const {
  const double c = std::cos(pose(2)), s = std::sin(pose(2));
  return {pose(0) + c * b_[i].x() - s * b_[i].y(), pose(1) + s * b_[i].x() + c * b_[i].y()};
}

int RRR3::ik(const Pose& pose, const Mode& mode, double* alpha) const {
  double c, s, Y[3], X[3], a[3];
  bool ok[3];
  vmath::sincos(&pose(2), &s, &c, 1);
  for (int i = 0; i < 3; ++i)
    ok[i] = leg_alpha_args(pose(0), pose(1), c, s, o_[i].x(), o_[i].y(), b_[i].x(), b_[i].y(), mode[i], l1_, l2_,
                           Y[i], X[i]);
  vmath::atan2(Y, X, a, 3);
  for (int i = 0; i < 3; ++i) {
    if (!ok[i]) {
      for (int j = i; j < 3; ++j) alpha[j] = kNaN;
      return i;
    }
    alpha[i] = a[i];
  }
  return -1;
}

void RRR3::ik_batch(const double* poses, long count, const Mode& mode, double* out, Progress* progress) const {
  kernel::RRR3Legs legs;
  for (int i = 0; i < 3; ++i) {
    legs.o[2 * i] = o_[i].x(), legs.o[2 * i + 1] = o_[i].y();
    legs.b[2 * i] = b_[i].x(), legs.b[2 * i + 1] = b_[i].y();
    legs.m[i] = mode[i];
  }
  legs.l1 = l1_, legs.l2 = l2_;
  kernel::rrr3_ik_batch(legs, poses, count, out, progress);
}

Eigen::Vector3d RRR3::ik_or_throw(const Pose& pose, const Mode& mode) const {
  Eigen::Vector3d alpha;
  const int leg = ik(pose, mode, alpha.data());
  if (leg >= 0) {
    const double r = (platform_joint(pose, leg) - o_[leg]).norm();
    throw LegUnreachable(leg, "pose: leg " + std::to_string(leg) + " cannot reach: |O_" + std::to_string(leg) + "B_" +
                                  std::to_string(leg) + "| = " + number(r) + " m is outside [" +
                                  number(std::abs(l1_ - l2_)) + ", " + number(l1_ + l2_) + "]");
  }
  return alpha;
}

void RRR3NewtonOptions::validate() const {
  if (max_iter < 0 || max_iter > kMaxNewtonIterations)
    throw std::invalid_argument("max_iter: must be in [0, " + std::to_string(kMaxNewtonIterations) + "], got " +
                                std::to_string(max_iter));
  if (!(std::isfinite(tol) && tol > 0)) throw std::invalid_argument("tol: must be a positive finite number");
}

RRR3Newton RRR3::ik_newton(const Pose& pose, const Eigen::Vector3d& alpha0, const Eigen::Vector3d& beta0,
                           const RRR3NewtonOptions& options) const {
  options.validate();
  const int max_iter = options.max_iter;
  const double tol = options.tol;
  RRR3Newton res;
  res.alpha = alpha0;
  res.beta = beta0;
  res.converged = true;
  // The 6 x 6 Jacobian of the loop equations is block diagonal (leg i involves only alpha_i and
  // beta_i), so the Newton step of the whole system is the three 2 x 2 steps.
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d target = platform_joint(pose, i);
    double& a = res.alpha(i);
    double& b = res.beta(i);
    auto residual = [&] {
      return (o_[i] + Eigen::Vector2d(l1_ * std::cos(a) + l2_ * std::cos(a + b), l1_ * std::sin(a) + l2_ * std::sin(a + b)) -
              target).norm();
    };
    int it = 0;
    for (;; ++it) {
      const double c1 = std::cos(a), s1 = std::sin(a), c12 = std::cos(a + b), s12 = std::sin(a + b);
      const Eigen::Vector2d f = o_[i] + Eigen::Vector2d(l1_ * c1 + l2_ * c12, l1_ * s1 + l2_ * s12) - target;
      if (f.norm() < tol || it >= max_iter) break;
      Eigen::Matrix2d J;
      J << -l1_ * s1 - l2_ * s12, -l2_ * s12, l1_ * c1 + l2_ * c12, l2_ * c12;
      const double det = J.determinant();
      if (!(std::abs(det) > 1e-14 * l1_ * l2_)) break;  // stretched or folded leg: no Newton step
      const Eigen::Vector2d step = J.inverse() * f;
      if (!step.allFinite()) break;  // keep the last finite iterate
      a -= step(0);
      b -= step(1);
    }
    a = wrap_angle(a);
    b = wrap_angle(b);
    // The answer is verified where it is returned: wrapping a far-off iterate moves it by rounding.
    const double err = residual();
    res.iterations = std::max(res.iterations, it);
    if (!(err < tol)) res.converged = false;
    res.error = std::max(res.error, err);
  }
  return res;
}

double RRR3::loops(const Eigen::Matrix<double, 3, 2>& A, const Pose& x, Eigen::Vector3d& f, Eigen::Matrix3d& J) const {
  double err = 0;
  const double c = std::cos(x(2)), s = std::sin(x(2));
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d rb(c * b_[i].x() - s * b_[i].y(), s * b_[i].x() + c * b_[i].y());
    const Eigen::Vector2d ab = x.head<2>() + rb - A.row(i).transpose();
    err = std::max(err, std::abs(ab.norm() - l2_));
    // (|AB|^2 - l2^2) / (2 l2): a length error, well scaled near the solution.
    f(i) = (ab.squaredNorm() - l2_ * l2_) / (2 * l2_);
    J.row(i) << ab.x() / l2_, ab.y() / l2_, (ab.y() * rb.x() - ab.x() * rb.y()) / l2_;
  }
  return err;
}

RRR3Fk RRR3::fk(const Eigen::Vector3d& alpha, const Pose& guess, const RRR3NewtonOptions& options) const {
  options.validate();
  return close_loops(elbows(alpha), guess, options);
}

RRR3Fk RRR3::close_loops(const Eigen::Matrix<double, 3, 2>& A, const Pose& guess,
                         const RRR3NewtonOptions& options) const {
  const int max_iter = options.max_iter;
  const double tol = options.tol;
  RRR3Fk res;
  Pose x = guess;
  for (int it = 0;; ++it) {
    Eigen::Vector3d f;
    Eigen::Matrix3d J;
    const double err = loops(A, x, f, J);
    res.iterations = it;
    res.error = err;
    if (!std::isfinite(err)) break;
    if (err < tol) {
      res.converged = true;
      break;
    }
    if (it >= max_iter) break;
    Eigen::FullPivLU<Eigen::Matrix3d> lu(J);
    if (lu.rank() < 3) break;  // parallel singularity: Newton cannot continue
    Eigen::Vector3d step = lu.solve(f);
    if (!step.allFinite()) break;  // keep the last finite iterate
    // Keep each step local so Newton stays in the assembly mode it started in.
    const double scale = std::max({1.0, std::abs(step(2)) / 0.3, step.head<2>().norm() / (0.3 * l2_)});
    x -= step / scale;
  }
  x(2) = wrap_angle(x(2));
  res.pose = x;
  // The answer is verified where it is returned: wrapping a far-off orientation moves it by rounding.
  res.error = closure_at(A, x, b_, l2_);  // closure_error(alpha, x), the elbows computed once
  res.converged = res.error < tol;
  return res;
}

double RRR3::closure_error(const Eigen::Vector3d& alpha, const Pose& pose) const {
  return closure_at(elbows(alpha), pose, b_, l2_);
}

Eigen::Matrix<double, 3, 2> RRR3::elbows(const Eigen::Vector3d& alpha) const {
  Eigen::Matrix<double, 3, 2> A;
  for (int i = 0; i < 3; ++i) A.row(i) = (o_[i] + l1_ * Eigen::Vector2d(std::cos(alpha(i)), std::sin(alpha(i)))).transpose();
  return A;
}

void RRR3::jacobians_at(const Pose& pose, const Eigen::Matrix<double, 3, 2>& elbows, Eigen::Matrix3d& A,
                        Eigen::Matrix3d& B) const {
  B.setZero();
  const Eigen::Vector2d e = pose.head<2>();
  const double c = std::cos(pose(2)), s = std::sin(pose(2));
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d a = elbows.row(i).transpose();
    const Eigen::Vector2d ab = platform_joint(pose, i) - a;
    const double n = ab.norm();
    // (cos g_i, sin g_i) with g_i = atan2(A_iB_i) - phi: the unit A_iB_i seen in the effector frame.
    A.row(i) << (c * ab.x() + s * ab.y()) / n, (c * ab.y() - s * ab.x()) / n, cross(ab, e - a) / n;
    B(i, i) = cross(ab, o_[i] - a) / n;
  }
}

void RRR3::jacobians(const Pose& pose, const Mode& mode, Eigen::Matrix3d& A, Eigen::Matrix3d& B) const {
  jacobians_at(pose, elbows(ik_or_throw(pose, mode)), A, B);
}

double RRR3::distance(const Eigen::Matrix3d& A) const {
  Eigen::Matrix3d As = A;
  As.col(2) /= re_;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(As.transpose() * As, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d l = eig.eigenvalues().cwiseMax(0.0);  // ascending
  return l(2) > 0 ? std::sqrt(l(0) / l(2)) : 0.0;
}

RRR3Singularity RRR3::singularity(const Pose& pose, const Mode& mode, double tol) const {
  if (!(std::isfinite(tol) && tol > 0)) throw std::invalid_argument("tol: must be a positive finite number");
  Eigen::Matrix3d A, B;
  const PoseMeasures m = measures_at(*this, pose, ik_or_throw(pose, mode), A, B);
  RRR3Singularity s;
  s.det_a = m.det_a;
  s.det_b = m.det_b;
  s.det_a_norm = m.det_a_norm;
  s.det_b_norm = m.det_b_norm;
  s.distance = distance(A);
  const SingularKind kind = singular_kind(s.det_a_norm, s.det_b_norm, tol);
  if (kind == SingularKind::Serial) {
    s.kind = "serial";
    B.diagonal().cwiseAbs().minCoeff(&s.leg);
  } else if (kind == SingularKind::Parallel) {
    s.kind = "parallel";
    // Lines A_iB_i parallel: the direction rows (cos g_i, sin g_i) are pairwise collinear.
    double worst = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        worst = std::max(worst, std::abs(A(i, 0) * A(j, 1) - A(i, 1) * A(j, 0)));
    s.lines = worst < std::sqrt(tol) ? "parallel" : "concurrent";
  }
  return s;
}

}  // namespace robokin
