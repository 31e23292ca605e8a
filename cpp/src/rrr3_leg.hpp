// The 3-RRR analytic inverse model of one leg, shared by RRR3::ik and the batch kernel so both
// give the same bits. Branch-free, so loops over poses vectorise.
#pragma once

#include <algorithm>
#include <cmath>

namespace robokin {

// alpha of a leg with base joint o and platform joint b (effector frame) at position (x, y) and
// orientation (c, s) = (cos phi, sin phi), elbow sign m, as alpha = atan2(Y, X) (vmath::atan2 over
// the legs or a batch, fast_math.hpp); false when the leg cannot reach (alpha is then NaN).
// The law of cosines gives the angle theta at O between OB and OA: cos theta = K / (2 l1 r),
// sin theta = S / (2 l1 r). Rotating OB by -m theta gives the direction of link 1, scaled by
// 2 l1 r > 0, which atan2 ignores: no acos, no division. r == 0 (possible when l1 == l2) leaves
// alpha free and counts as unreachable.
inline bool leg_alpha_args(double x, double y, double c, double s, double ox, double oy, double bx, double by,
                           double m, double l1, double l2, double& Y, double& X) {
  const double dx = x + c * bx - s * by - ox, dy = y + s * bx + c * by - oy;
  const double r2 = dx * dx + dy * dy;
  const bool ok = (r2 >= (l1 - l2) * (l1 - l2)) & (r2 <= (l1 + l2) * (l1 + l2)) & (r2 > 0);
  const double K = l1 * l1 + r2 - l2 * l2;
  const double S = m * std::sqrt(std::max(0.0, 4 * l1 * l1 * r2 - K * K));
  Y = K * dy - S * dx;
  X = K * dx + S * dy;
  return ok;
}

}  // namespace robokin
