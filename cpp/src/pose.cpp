#include "robokin/pose.hpp"
#include "robokin/task.hpp"

#include <cmath>

namespace robokin {

Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch),
               cy = std::cos(yaw), sy = std::sin(yaw);
  Eigen::Matrix3d R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return R;
}

Eigen::Vector3d matrix_to_rpy(const Eigen::Matrix3d& R) {
  const double cp = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cp);
  if (cp > 1e-10) return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
  // Gimbal lock: R = Rz(yaw -+ roll) Ry(+-pi/2); roll = 0 puts it all in yaw.
  return {0.0, pitch, std::atan2(-R(0, 1), R(1, 1))};
}

// Shepperd's method: the largest of 4w^2, 4x^2, 4y^2, 4z^2 is taken from the diagonal (no
// cancellation), the other three from off-diagonal sums and differences divided by it.
Eigen::Vector4d matrix_to_quaternion(const Eigen::Matrix3d& R) {
  const double t = R.trace();
  Eigen::Vector4d q;
  if (t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + t);  // 4w
    q << 0.25 * s, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s;
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2));  // 4x
    q << (R(2, 1) - R(1, 2)) / s, 0.25 * s, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s;
  } else if (R(1, 1) >= R(2, 2)) {
    const double s = 2.0 * std::sqrt(1.0 + R(1, 1) - R(0, 0) - R(2, 2));  // 4y
    q << (R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, 0.25 * s, (R(1, 2) + R(2, 1)) / s;
  } else {
    const double s = 2.0 * std::sqrt(1.0 + R(2, 2) - R(0, 0) - R(1, 1));  // 4z
    q << (R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, 0.25 * s;
  }
  if (q(0) < 0) q = -q;
  return q.normalized();
}

Eigen::Matrix3d quaternion_to_matrix(const Eigen::Vector4d& q_in) {
  const Eigen::Vector4d q = q_in / q_in.stableNorm();
  const double w = q(0), x = q(1), y = q(2), z = q(3);
  Eigen::Matrix3d R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

Eigen::Vector4d quaternion_multiply(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  return {a(0) * b(0) - a(1) * b(1) - a(2) * b(2) - a(3) * b(3),
          a(0) * b(1) + a(1) * b(0) + a(2) * b(3) - a(3) * b(2),
          a(0) * b(2) - a(1) * b(3) + a(2) * b(0) + a(3) * b(1),
          a(0) * b(3) + a(1) * b(2) - a(2) * b(1) + a(3) * b(0)};
}

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w(2), w(1), w(2), 0, -w(0), -w(1), w(0), 0;
  return S;
}

// (1 - cos t) / t^2 and (t - sin t) / t^3 for t < 1e-2, by their series (no cancellation).
void rodrigues_coefficients(double t, double& b, double& c) {
  const double t2 = t * t;
  b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
  c = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0;
}

}  // namespace

// Below 1e-2 rad the series in w itself; above, Rodrigues with the unit axis k = w / |w| and the
// coefficients written for it (bounded for any angle, also near the largest doubles).
Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w) {
  double t = w.norm();
  if (!std::isfinite(t)) t = w.stableNorm();
  if (t < 1e-2) {
    double b, c;
    rodrigues_coefficients(t, b, c);
    const Eigen::Matrix3d S = skew(w);
    return Eigen::Matrix3d::Identity() + (1.0 - t * t * c) * S + b * S * S;  // sin t / t = 1 - t^2 c
  }
  const Eigen::Matrix3d K = skew(w / t);
  const double h = std::sin(0.5 * t);
  return Eigen::Matrix3d::Identity() + std::sin(t) * K + (2.0 * h * h) * K * K;
}

Rigid se3_exp(const Vector6& xi) {
  const Eigen::Vector3d v = xi.head<3>(), w = xi.tail<3>();
  double t = w.norm();
  if (!std::isfinite(t)) t = w.stableNorm();
  Eigen::Matrix3d V;
  if (t < 1e-2) {
    double b, c;
    rodrigues_coefficients(t, b, c);
    const Eigen::Matrix3d S = skew(w);
    V = Eigen::Matrix3d::Identity() + b * S + c * S * S;
  } else {  // V = I + (1 - cos t) / t K + (1 - sin t / t) K^2, K the unit axis' skew matrix
    const Eigen::Matrix3d K = skew(w / t);
    const double h = std::sin(0.5 * t);
    V = Eigen::Matrix3d::Identity() + (2.0 * h * h / t) * K + (1.0 - std::sin(t) / t) * K * K;
  }
  return {rotation_exp(w), V * v};
}

Vector6 se3_log(const Rigid& T) {
  const Eigen::Vector3d w = rotation_vector(T.R);
  const double t = w.norm();
  // V^-1 = I - S / 2 + d S^2, d = (1 - (t / 2) cot(t / 2)) / t^2.
  double d;
  if (t < 1e-2) {
    const double t2 = t * t;
    d = 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0;
  } else {
    const double h = 0.5 * t;
    d = (1.0 - h * std::cos(h) / std::sin(h)) / (t * t);
  }
  const Eigen::Matrix3d S = skew(w);
  Vector6 xi;
  xi.head<3>() = T.p - 0.5 * (S * T.p) + d * (S * (S * T.p));
  xi.tail<3>() = w;
  return xi;
}

Vector6 pose_error(const Rigid& target, const Rigid& current) {
  Target t;
  t.task = Task::Pose;
  t.pose = target;
  Vector6 e;
  task_error(t, current, e.data());
  return e;
}

}  // namespace robokin
