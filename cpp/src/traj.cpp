#include "robokin/traj.hpp"
#include "robokin/pose.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

// --- quintic ------------------------------------------------------------------------------------

Quintic::Quintic(const Vector& q0, const Vector& q1, const Vector& qd0, const Vector& qd1, double t0, double t1)
    : q0_(q0), q1_(q1), qd0_(qd0), qd1_(qd1), t0_(t0), t1_(t1), c_(q0.size(), 6) {
  if (!(t1 > t0)) throw std::invalid_argument("t: the last time must be after the first");
  const double T = t1 - t0;
  for (int i = 0; i < q0.size(); ++i) {
    const double d = q1(i) - q0(i), v0 = T * qd0(i), v1 = T * qd1(i);
    c_.row(i) << q0(i), v0, 0.0, 10 * d - 6 * v0 - 4 * v1, -15 * d + 8 * v0 + 7 * v1, 6 * d - 3 * v0 - 3 * v1;
  }
}

void Quintic::evaluate(const double* t, long begin, long end, const JointSamples& out) const {
  const int n = dof();
  const double T = t1_ - t0_, iT = 1.0 / T, iT2 = iT * iT;
  for (long k = begin; k < end; ++k) {
    double* q = out.q + k * n;
    double* qd = out.qd + k * n;
    double* qdd = out.qdd + k * n;
    if (!(t[k] > t0_) || !(t[k] < t1_)) {  // the boundary values, exactly
      const bool start = !(t[k] > t0_);
      for (int i = 0; i < n; ++i) {
        q[i] = start ? q0_(i) : q1_(i);
        qd[i] = start ? qd0_(i) : qd1_(i);
        qdd[i] = 0.0;
      }
      continue;
    }
    const double s = (t[k] - t0_) * iT;
    for (int i = 0; i < n; ++i) {
      const double c1 = c_(i, 1), c3 = c_(i, 3), c4 = c_(i, 4), c5 = c_(i, 5);
      q[i] = c_(i, 0) + s * (c1 + s * s * (c3 + s * (c4 + s * c5)));
      qd[i] = (c1 + s * s * (3 * c3 + s * (4 * c4 + s * 5 * c5))) * iT;
      qdd[i] = s * (6 * c3 + s * (12 * c4 + s * 20 * c5)) * iT2;
    }
  }
}

// --- trapezoid ----------------------------------------------------------------------------------

namespace {
// The shortest time to move a distance d >= 0 from rest to rest with |v| <= vmax, |a| <= amax.
double fastest(double d, double vmax, double amax) {
  if (d == 0) return 0.0;
  return d >= vmax * (vmax / amax) ? d / vmax + vmax / amax : 2.0 * std::sqrt(d / amax);
}
}  // namespace

Trapezoid::Trapezoid(const Vector& q0, const Vector& q1, const Vector& vmax, const Vector& amax)
    : q0_(q0), q1_(q1), v_(Vector::Zero(q0.size())), a_(amax), ta_(Vector::Zero(q0.size())) {
  const int n = dof();
  for (int i = 0; i < n; ++i) T_ = std::max(T_, fastest(std::abs(q1(i) - q0(i)), vmax(i), amax(i)));
  if (!std::isfinite(T_)) throw std::invalid_argument("q1: the motion's duration is not finite (distance too large for the limits)");
  for (int i = 0; i < n; ++i) {
    const double d = std::abs(q1(i) - q0(i)), a = amax(i);
    if (d == 0) continue;
    // The cruise speed v that arrives at T: d = v T - v^2 / a, the smaller root, in the form
    // without cancellation; the time-optimal joint gets its own limit (or its triangle's peak).
    const double disc = std::max(0.0, a * T_ * (a * T_) - 4.0 * a * d);
    const double v = std::min(vmax(i), 2.0 * a * d / (a * T_ + std::sqrt(disc)));
    v_(i) = v;
    ta_(i) = std::min(0.5 * T_, v / a);
  }
}

void Trapezoid::evaluate(const double* t, long begin, long end, const JointSamples& out) const {
  const int n = dof();
  for (long k = begin; k < end; ++k) {
    const double tk = t[k];
    double* q = out.q + k * n;
    double* qd = out.qd + k * n;
    double* qdd = out.qdd + k * n;
    for (int i = 0; i < n; ++i) {
      const double sign = q1_(i) > q0_(i) ? 1.0 : -1.0, a = a_(i), v = v_(i), ta = ta_(i);
      if (q1_(i) == q0_(i)) {  // a joint that does not move
        q[i] = q0_(i), qd[i] = qdd[i] = 0.0;
      } else if (!(tk < T_)) {  // the end, exactly
        q[i] = q1_(i), qd[i] = qdd[i] = 0.0;
      } else if (!(tk > 0)) {
        q[i] = q0_(i), qd[i] = 0.0, qdd[i] = sign * a;
      } else if (tk < ta) {
        q[i] = q0_(i) + sign * (0.5 * a * tk * tk), qd[i] = sign * a * tk, qdd[i] = sign * a;
      } else if (tk <= T_ - ta) {
        q[i] = q0_(i) + sign * v * (tk - 0.5 * ta), qd[i] = sign * v, qdd[i] = 0.0;
      } else {
        const double r = T_ - tk;
        q[i] = q1_(i) - sign * (0.5 * a * r * r), qd[i] = sign * a * r, qdd[i] = -sign * a;
      }
    }
  }
}

// --- via points ---------------------------------------------------------------------------------

ViaPath::ViaPath(const Eigen::MatrixXd& points, const Vector& vmax, const Vector& amax) {
  const long n = points.cols();
  std::vector<long> keep{0};
  for (long k = 1; k < points.rows(); ++k)
    if (points.row(k) != points.row(keep.back())) keep.push_back(k);
  const long M = static_cast<long>(keep.size()), S = M - 1;
  p_.resize(M, n);
  for (long k = 0; k < M; ++k) p_.row(k) = points.row(keep[k]);
  v_ = Eigen::MatrixXd::Zero(std::max(0L, S), n);
  tau_ = Vector::Zero(M);
  tb_ = Vector::Zero(M);
  if (S == 0) return;
  // Segment durations at the velocity limits.
  Vector seg(S);
  for (long j = 0; j < S; ++j)
    seg(j) = ((p_.row(j + 1) - p_.row(j)).cwiseAbs().transpose().array() / vmax.array()).maxCoeff();
  if (!seg.allFinite() || !(seg.array() > 0).all())
    throw std::invalid_argument("points: the motion's duration is not finite (distance too large for the limits)");
  Vector need(S);
  auto blends = [&] {  // velocities and blend durations for the current segment durations
    for (long j = 0; j < S; ++j) v_.row(j) = (p_.row(j + 1) - p_.row(j)) / seg(j);
    for (long k = 0; k < M; ++k) {
      double tb = 0.0;
      for (long i = 0; i < n; ++i) {
        const double before = k > 0 ? v_(k - 1, i) : 0.0, after = k < S ? v_(k, i) : 0.0;
        tb = std::max(tb, std::abs(after - before) / amax(i));
      }
      tb_(k) = tb;
    }
    double worst = 0.0;
    for (long j = 0; j < S; ++j) {
      need(j) = 0.5 * (tb_(j) + tb_(j + 1));
      worst = std::max(worst, need(j) / seg(j));
    }
    return worst;
  };
  // Lengthen the segments too short for their half blends (this changes the blends next to them:
  // a few passes), then, if some still are, slow the whole path down by one factor c: the
  // velocities scale by 1 / c, so do the blends, and the segments by c.
  double worst = blends();
  for (int pass = 0; pass < 100 && worst > 1.0; ++pass) {
    for (long j = 0; j < S; ++j) seg(j) = std::max(seg(j), need(j) * (1.0 + 1e-12));
    worst = blends();
  }
  if (worst > 1.0) {
    seg *= std::sqrt(worst) * (1.0 + 1e-9);
    worst = blends();
  }
  if (!seg.allFinite() || !tb_.allFinite())
    throw std::invalid_argument("points: the motion's duration is not finite (distance too large for the limits)");
  tau_(0) = 0.5 * tb_(0);
  for (long j = 0; j < S; ++j) tau_(j + 1) = tau_(j) + seg(j);
  T_ = tau_(S) + 0.5 * tb_(S);
  if (!std::isfinite(T_))
    throw std::invalid_argument("points: the motion's duration is not finite (distance too large for the limits)");
}

void ViaPath::evaluate(const double* t, long begin, long end, const JointSamples& out) const {
  const long M = p_.rows(), n = p_.cols(), S = M - 1;
  for (long k = begin; k < end; ++k) {
    const double tk = t[k];
    double* q = out.q + k * n;
    double* qd = out.qd + k * n;
    double* qdd = out.qdd + k * n;
    if (S == 0 || !(tk > 0) || !(tk < T_)) {  // at rest on the first or the last point, exactly
      const long at = (S == 0 || !(tk > 0)) ? 0 : S;
      for (long i = 0; i < n; ++i) q[i] = p_(at, i), qd[i] = qdd[i] = 0.0;
      continue;
    }
    // The via point whose blend started last: blends start at tau - tb / 2, in increasing order.
    long lo = 0, hi = S;
    while (lo < hi) {
      const long mid = (lo + hi + 1) / 2;
      if (tau_(mid) - 0.5 * tb_(mid) <= tk) lo = mid;
      else hi = mid - 1;
    }
    const long j = lo;
    const double dt = tk - tau_(j), tb = tb_(j);
    if (tb > 0 && dt < 0.5 * tb) {  // in the blend around via j
      const double u = dt + 0.5 * tb;
      for (long i = 0; i < n; ++i) {
        const double before = j > 0 ? v_(j - 1, i) : 0.0, after = j < S ? v_(j, i) : 0.0;
        const double acc = (after - before) / tb;
        q[i] = p_(j, i) + before * dt + 0.5 * acc * u * u;
        qd[i] = before + acc * u;
        qdd[i] = acc;
      }
    } else {  // on the straight segment from via j
      for (long i = 0; i < n; ++i) {
        const double v = j < S ? v_(j, i) : 0.0;
        q[i] = p_(j, i) + v * dt, qd[i] = v, qdd[i] = 0.0;
      }
    }
  }
}

// --- Cartesian line -----------------------------------------------------------------------------

CartesianLine::CartesianLine(const Rigid& T0, const Rigid& T1) : T0_(T0), T1_(T1) {
  const Eigen::Vector3d d = T1.p - T0.p;
  length_ = d.norm();
  if (!std::isfinite(length_) || (length_ == 0 && d != Eigen::Vector3d::Zero())) length_ = d.stableNorm();
  if (!std::isfinite(length_)) throw std::invalid_argument("T1: too far from T0 (the distance is not finite)");
  u_ = length_ > 0 ? Eigen::Vector3d(d / length_) : Eigen::Vector3d::Zero();
  q0_ = matrix_to_quaternion(T0.R);
  // The relative rotation R0^T R1 as a quaternion with w >= 0: the shorter of the two arcs.
  const Eigen::Vector4d rel = matrix_to_quaternion(T0.R.transpose() * T1.R);
  const double s = rel.tail<3>().norm();
  angle_ = 2.0 * std::atan2(s, rel(0));
  axis_ = s > 0 ? Eigen::Vector3d(rel.tail<3>() / s) : Eigen::Vector3d::UnitX();
  if (s == 0) angle_ = 0.0;
  waxis_ = T0.R * axis_;
}

void CartesianLine::evaluate(const double* x, const double* xd, const double* xdd, long begin, long end,
                             double* poses, double* velocity, double* acceleration) const {
  for (long k = begin; k < end; ++k) {
    const double dist = x[2 * k], ang = x[2 * k + 1];
    Rigid T;
    if (dist == 0 && ang == 0) {
      T = T0_;  // the start, exactly (also the only pose of a line that does not move)
    } else if (dist == length_ && ang == angle_) {
      T = T1_;  // the end, exactly
    } else {
      T.p = length_ > 0 ? Eigen::Vector3d(T0_.p + (dist / length_) * (T1_.p - T0_.p)) : T0_.p;
      if (length_ > 0 && dist == length_) T.p = T1_.p;
      // SLERP: q(s) = q0 * (cos(s angle / 2), sin(s angle / 2) axis), s = ang / angle.
      const double h = 0.5 * ang;
      Eigen::Vector4d step;
      step << std::cos(h), std::sin(h) * axis_;
      T.R = ang == 0 ? T0_.R : quaternion_to_matrix(quaternion_multiply(q0_, step));
      if (ang == angle_ && angle_ > 0) T.R = T1_.R;
    }
    double* m = poses + 16 * k;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m[4 * r + c] = T.R(r, c);
      m[4 * r + 3] = T.p(r);
    }
    m[12] = m[13] = m[14] = 0.0;
    m[15] = 1.0;
    for (int i = 0; i < 3; ++i) {
      velocity[6 * k + i] = u_(i) * xd[2 * k];
      velocity[6 * k + 3 + i] = waxis_(i) * xd[2 * k + 1];
      acceleration[6 * k + i] = u_(i) * xdd[2 * k];
      acceleration[6 * k + 3 + i] = waxis_(i) * xdd[2 * k + 1];
    }
  }
}

// --- sample times -------------------------------------------------------------------------------

std::vector<double> sample_times(double duration, double dt, long max_samples) {
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("dt: must be a positive finite number");
  const double steps = std::floor(duration / dt);
  if (!(steps < static_cast<double>(max_samples)))
    throw std::invalid_argument("dt: the trajectory would have more than " + std::to_string(max_samples) +
                                " samples (duration " + std::to_string(duration) + " s); choose a larger dt");
  const long count = static_cast<long>(steps);
  std::vector<double> t;
  t.reserve(count + 2);
  for (long k = 0; k <= count; ++k) {
    const double tk = static_cast<double>(k) * dt;
    if (tk >= duration && k > 0) break;
    t.push_back(tk);
  }
  if (duration > 0 && t.back() < duration) {
    // A last regular sample a hair before the end would make a step of ~0: drop it.
    if (t.size() > 1 && duration - t.back() < 1e-9 * dt) t.pop_back();
    t.push_back(duration);
  }
  return t;
}

}  // namespace robokin
