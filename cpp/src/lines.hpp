// Two lines in space, each a point and a unit direction: their distance and nearest points (the
// joint axes of closed_family and of the UR layout's reading).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace robokin {

// The nearest points of the lines p + t a and q + u b (a, b unit, not parallel): on the first
// into `on_a`, on the second into `on_b` ((on_b - on_a) perpendicular to a and b).
inline void nearest_points(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& q,
                           const Eigen::Vector3d& b, Eigen::Vector3d& on_a, Eigen::Vector3d& on_b) {
  const Eigen::Vector3d w = q - p;
  const double ab = a.dot(b), wa = w.dot(a), wb = w.dot(b), den = 1.0 - ab * ab;
  const double t = (wa - ab * wb) / den, u = (ab * wa - wb) / den;
  on_a = p + t * a, on_b = q + u * b;
}

// Distance between the lines p + t a and q + u b (a, b unit); `nearest`, when given and the lines
// are not parallel (|a x b| >= 1e-12), receives the midpoint of their nearest points.
inline double line_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& q,
                            const Eigen::Vector3d& b, Eigen::Vector3d* nearest = nullptr) {
  const Eigen::Vector3d w = q - p;
  const Eigen::Vector3d n = a.cross(b);
  const double s = n.norm();
  if (s < 1e-12) return (w - w.dot(a) * a).norm();
  if (nearest) {
    Eigen::Vector3d on_a, on_b;
    nearest_points(p, a, q, b, on_a, on_b);
    *nearest = 0.5 * (on_a + on_b);
  }
  return std::abs(w.dot(n)) / s;
}

// The point of the line q + u b (b unit) nearest to x.
inline Eigen::Vector3d foot_on_line(const Eigen::Vector3d& x, const Eigen::Vector3d& q, const Eigen::Vector3d& b) {
  return q + (x - q).dot(b) * b;
}

}  // namespace robokin
