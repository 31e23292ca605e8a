// The DH layouts of the UR and the spherical-wrist closed forms (ik_closed.hpp's URArm and
// SphericalArm) read from a chain's geometry: whatever describes the chain (DH rows, a URDF, joints
// and frames), its joint axes at q = 0 decide.
#include "robokin/closed_family.hpp"
#include "robokin/ik_closed.hpp"

#include "chain_lazy.hpp"
#include "lines.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

[[noreturn]] void not_ur(const std::string& why) {
  throw std::invalid_argument("robot: not an arm of the UR layout (" + why + ")");
}

[[noreturn]] void not_spherical(const std::string& why) {
  throw std::invalid_argument("robot: not an arm of the spherical-wrist layout (" + why + ")");
}

// The DH angle about z from x0 to x1 (both normal to z).
double angle_about(const Eigen::Vector3d& z, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1) {
  return std::atan2(x0.cross(x1).dot(z), x0.dot(x1));
}

// The layout's tolerances: angles (rad) and distances (times the arm's size), as tight as the
// forward model's check of every solution, so that an arm that passes is solved to that check.
constexpr double kTolAngle = 1e-9, kTolDistance = 1e-9;

using Refusal = void (*)(const std::string&);

std::string axes_pair(int i, int j) { return "axes " + std::to_string(i + 1) + " and " + std::to_string(j + 1); }

// Axes i and j (0-based) at a right angle, else `refuse`.
void right_angle(const JointAxes& g, int i, int j, Refusal refuse) {
  if (std::abs(g.axis[i].dot(g.axis[j])) > kTolAngle) refuse(axes_pair(i, j) + " are not perpendicular");
}

// Axes i and j (0-based) meet at a right angle; their meeting point.
Eigen::Vector3d right_angle_meeting(const JointAxes& g, int i, int j, double tol_d, Refusal refuse) {
  right_angle(g, i, j, refuse);
  Eigen::Vector3d c;
  if (line_distance(g.point[i], g.axis[i], g.point[j], g.axis[j], &c) > tol_d) refuse(axes_pair(i, j) + " do not meet");
  return c;
}

// Six joints, every one revolute, else `refuse`.
void require_revolute_6r(const JointAxes& g, Refusal refuse) {
  if (g.axis.size() != 6) refuse("it has " + std::to_string(g.axis.size()) + " joints, not 6");
  for (int i = 0; i < 6; ++i)
    if (g.prismatic[i]) refuse("joint " + std::to_string(i + 1) + " is prismatic");
}

// The frame of DH axes x, z (z x x for y) at origin o.
Rigid dh_frame(const Eigen::Vector3d& x, const Eigen::Vector3d& z, const Eigen::Vector3d& o) {
  Rigid F;
  F.R.col(0) = x, F.R.col(1) = z.cross(x), F.R.col(2) = z;
  F.p = o;
  return F;
}

// Standard DH frames are placed on the axes: z_{i-1} along axis i (its direction, or against it
// for joints 3 and 4 when their axes point against axis 2's: scale -1), the origins at the
// meeting points of axes 1, 2 (frames 0 and 1: d1 = 0), 4, 5 and 5, 6, and on axes 3 and 4 at the
// feet of the common normals from the previous origin (d2 = d3 = 0); x1 = z0 x z1 (alpha1 = pi/2),
// x4 = z3 x z4 (pi/2), x5 = z5 x z4 (-pi/2), x2 and x3 along the normals (a2, a3 > 0), x0 = x1.
// The fixed frames before joint 1 and after joint 6 at q = 0 are the base and the tool.
URArm ur_arm_of(const JointAxes& g) {
  require_revolute_6r(g, not_ur);
  const double tol_d = kTolDistance * std::max(1.0, g.size);
  URArm arm;
  Eigen::Vector3d z[6];
  for (int i = 0; i < 6; ++i) {
    const bool parallel = i == 2 || i == 3;  // to axis 2: its direction, the scale's sign
    if (parallel && g.axis[i].cross(g.axis[1]).norm() > kTolAngle) not_ur("axes 2, 3, 4 are not parallel");
    arm.scale[i] = parallel && g.axis[i].dot(g.axis[1]) < 0 ? -1.0 : 1.0;
    z[i] = arm.scale[i] * g.axis[i];
  }
  const Eigen::Vector3d o1 = right_angle_meeting(g, 0, 1, tol_d, not_ur);
  const Eigen::Vector3d o4 = right_angle_meeting(g, 3, 4, tol_d, not_ur);
  const Eigen::Vector3d o5 = right_angle_meeting(g, 4, 5, tol_d, not_ur);
  const Eigen::Vector3d o2 = foot_on_line(o1, g.point[2], z[2]), o3 = foot_on_line(o2, g.point[3], z[3]);
  arm.a2 = (o2 - o1).stableNorm(), arm.a3 = (o3 - o2).stableNorm();
  if (arm.a2 <= tol_d || arm.a3 <= tol_d) not_ur("axes 2, 3, 4 do not stand apart (a2 and a3 must not be 0)");
  Eigen::Vector3d x[6];
  x[1] = z[0].cross(z[1]).normalized(), x[0] = x[1];
  x[2] = (o2 - o1) / arm.a2, x[3] = (o3 - o2) / arm.a3;
  x[4] = z[3].cross(z[4]).normalized(), x[5] = z[5].cross(z[4]).normalized();
  for (int i = 0; i < 5; ++i) arm.theta[i] = angle_about(z[i], x[i], x[i + 1]);
  arm.d1 = 0.0, arm.d4 = (o4 - o3).dot(z[3]), arm.d5 = (o5 - o4).dot(z[4]);
  arm.base = dh_frame(x[0], z[0], o1);
  arm.tool = dh_frame(x[5], z[5], o5).inverse() * g.tool;
  arm.size = std::abs(arm.d1) + arm.a2 + arm.a3 + std::abs(arm.d4) + std::abs(arm.d5) + arm.base.p.stableNorm() +
             arm.tool.p.stableNorm();
  return arm;
}

// Standard DH frames on the axes as ur_arm places them, z_{i-1} along axis i (against it for
// joint 3 when axis 3 points against axis 2: scale -1): the common normal of axes 1 and 2 gives
// frame 0's origin on axis 1 (d1 = 0), frame 1's on axis 2 and x1 = z0 x z1 (alpha1 = pi/2, a1
// signed along it); frame 2's origin is the foot on axis 3 from frame 1's (d2 = 0, x2 along it,
// a2 > 0); the common normal of axes 3 and 4 gives d3 along axis 3 and frame 3's origin on axis 4
// with x3 = z3 x z2 (alpha3 = -pi/2, a3 signed along it); frames 4 and 5 sit at the wrist centre
// with x4 = z3 x z4 (pi/2) and x5 = z5 x z4 (-pi/2); x0 = x1.
SphericalArm spherical_arm_of(const JointAxes& g) {
  require_revolute_6r(g, not_spherical);
  const double tol_d = kTolDistance * std::max(1.0, g.size);
  SphericalArm sa;
  if (g.axis[2].cross(g.axis[1]).norm() > kTolAngle) not_spherical("axes 2 and 3 are not parallel");
  sa.scale[2] = g.axis[2].dot(g.axis[1]) < 0 ? -1.0 : 1.0;
  Eigen::Vector3d z[6];
  for (int i = 0; i < 6; ++i) z[i] = sa.scale[i] * g.axis[i];
  right_angle(g, 0, 1, not_spherical);
  right_angle(g, 2, 3, not_spherical);
  const Eigen::Vector3d c = right_angle_meeting(g, 3, 4, tol_d, not_spherical);
  if ((right_angle_meeting(g, 4, 5, tol_d, not_spherical) - c).norm() > tol_d)
    not_spherical("axes 4, 5, 6 do not meet in one point");
  Eigen::Vector3d o0, o1, f2, o3;
  nearest_points(g.point[0], z[0], g.point[1], z[1], o0, o1);
  const Eigen::Vector3d o2 = foot_on_line(o1, g.point[2], z[2]);
  nearest_points(g.point[2], z[2], g.point[3], z[3], f2, o3);
  ArmGeometry& arm = sa.arm;
  arm.a2 = (o2 - o1).stableNorm();
  if (arm.a2 <= tol_d) not_spherical("axes 2 and 3 do not stand apart (a2 must not be 0)");
  Eigen::Vector3d x[6];
  x[1] = z[0].cross(z[1]).normalized(), x[0] = x[1];
  x[2] = (o2 - o1) / arm.a2;
  x[3] = z[3].cross(z[2]).normalized();
  x[4] = z[3].cross(z[4]).normalized(), x[5] = z[5].cross(z[4]).normalized();
  for (int i = 0; i < 5; ++i) sa.theta[i] = angle_about(z[i], x[i], x[i + 1]);
  arm.a1 = (o1 - o0).dot(x[1]), arm.d1 = 0.0;
  arm.a3 = (o3 - f2).dot(x[3]), arm.d3 = (f2 - o2).dot(z[2]), arm.d4 = (c - o3).dot(z[3]);
  if (std::hypot(arm.a3, arm.d4) <= tol_d) not_spherical("the wrist centre is on axis 3 (the forearm has no length)");
  sa.base = dh_frame(x[0], z[0], o0);
  sa.tool = dh_frame(x[5], z[5], c).inverse() * g.tool;
  sa.size = arm.size() + sa.base.p.stableNorm() + sa.tool.p.stableNorm();
  return sa;
}

// read(g), or none when the axes do not have its layout.
template <class Read>
auto layout(const JointAxes& g, Read read) -> std::optional<decltype(read(g))> {
  try {
    return read(g);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

}  // namespace

URArm ur_arm(const Chain& chain) { return ur_arm_of(joint_axes(chain)); }
SphericalArm spherical_arm(const Chain& chain) { return spherical_arm_of(joint_axes(chain)); }

ClosedLayout read_closed_layout(const Chain& chain) {
  const JointAxes g = joint_axes(chain);
  ClosedLayout l;
  l.ur = layout(g, ur_arm_of);
  if (!l.ur) l.spherical = layout(g, spherical_arm_of);
  return l;
}

const ClosedLayout& Chain::closed_layout() const {
  std::call_once(lazy_->layout_once,
                 [this] { lazy_->layout = std::make_unique<const ClosedLayout>(read_closed_layout(*this)); });
  return *lazy_->layout;
}

}  // namespace robokin
