#include "robokin/rpr.hpp"

#include <cmath>
#include <limits>

namespace robokin {

void rpr_self_motion(const Eigen::Vector2d& p, const double* t1, long count, double l1, double l3,
                     const Vector& lower, const Vector& upper, double* out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double t3_floor = std::isfinite(lower(2)) ? lower(2) : -M_PI;
  for (long k = 0; k < count; ++k) {
    const Eigen::Vector2d u(std::cos(t1[k]), std::sin(t1[k]));
    // |p - r u|^2 = L3^2  <=>  r^2 - 2 (p.u) r + |p|^2 - L3^2 = 0
    const double b = p.dot(u), disc = b * b - p.squaredNorm() + l3 * l3;
    for (int branch = 0; branch < 2; ++branch) {
      double* row = out + 3 * (branch * count + k);
      row[0] = row[1] = row[2] = nan;
      if (disc < 0) continue;
      const double r = branch == 0 ? b - std::sqrt(disc) : b + std::sqrt(disc);
      const Eigen::Vector2d w = p - r * u;
      double t3 = std::atan2(w.y(), w.x()) - t1[k];
      t3 = t3_floor + std::fmod(std::fmod(t3 - t3_floor, 2 * M_PI) + 2 * M_PI, 2 * M_PI);
      const double q[3] = {t1[k], r - l1, t3};
      bool inside = true;
      for (int i = 0; i < 3; ++i) inside = inside && q[i] >= lower(i) && q[i] <= upper(i);
      if (inside) row[0] = q[0], row[1] = q[1], row[2] = q[2];
    }
  }
}

}  // namespace robokin
