#include "robokin/rpr.hpp"
#include "robokin/limits.hpp"

#include <cmath>
#include <limits>

namespace robokin {

void rpr_self_motion(const Eigen::Vector2d& p, const double* t1, long count, double l1, double l3,
                     const Vector& lower, const Vector& upper, double* out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
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
      const double d = r - l1;
      if (t1[k] >= lower(0) && t1[k] <= upper(0) && d >= lower(1) && d <= upper(1) &&
          settle_into_limits(t3, lower(2), upper(2), true))
        row[0] = t1[k], row[1] = d, row[2] = t3;
    }
  }
}

}  // namespace robokin
