// A chain's joint axes at the zero configuration and the closed-form family they allow.
#include "robokin/closed_family.hpp"

#include <Eigen/Geometry>
#include <kdl/segment.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace robokin {
namespace {

Eigen::Vector3d vec(const KDL::Vector& v) { return {v.x(), v.y(), v.z()}; }

// Angle between the directions of two unit axes, as lines (0 for opposite directions too).
double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

// Distance between the lines of axes i and j, and the midpoint of their nearest points (for
// parallel lines, the distance only).
double line_distance(const JointAxes& g, int i, int j, Eigen::Vector3d* nearest = nullptr) {
  const Eigen::Vector3d &a = g.axis[i], &b = g.axis[j];
  const Eigen::Vector3d w = g.point[j] - g.point[i];
  const Eigen::Vector3d n = a.cross(b);
  const double s = n.norm();
  if (s < 1e-12) return (w - w.dot(a) * a).norm();
  if (nearest) {
    // Nearest points p_i + t a, p_j + u b: (w - t a + u b) perpendicular to a and b.
    const double ab = a.dot(b), wa = w.dot(a), wb = w.dot(b), den = 1.0 - ab * ab;
    const double t = (wa - ab * wb) / den, u = (ab * wa - wb) / den;
    *nearest = 0.5 * ((g.point[i] + t * a) + (g.point[j] + u * b));
  }
  return std::abs(w.dot(n)) / s;
}

std::string axes_text(std::initializer_list<int> axes) {  // 0-based in, "axes 2, 3, 4" out
  std::string s = "axes ";
  for (int i : axes) s += (s.size() > 5 ? ", " : "") + std::to_string(i + 1);
  return s;
}

std::string mm(double metres) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g mm apart", metres * 1e3);
  return buf;
}

std::string degrees(double radians) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g deg apart", radians * 180.0 / M_PI);
  return buf;
}

// How far axes 4, 5, 6 (from first) are from meeting in one point: the larger of the distance of
// axes first, first + 1 and that of their meeting point from axis first + 2. Sets `center`.
double wrist_gap(const JointAxes& g, int first, Eigen::Vector3d& center) {
  if (line_angle(g.axis[first], g.axis[first + 1]) < 1e-9) return INFINITY;
  const double d = line_distance(g, first, first + 1, &center);
  const Eigen::Vector3d w = center - g.point[first + 2];
  return std::max(d, (w - w.dot(g.axis[first + 2]) * g.axis[first + 2]).norm());
}

// The largest angle between consecutive axes of first .. last.
double parallel_gap(const JointAxes& g, int first, int last) {
  double gap = 0;
  for (int i = first; i < last; ++i) gap = std::max(gap, line_angle(g.axis[i], g.axis[i + 1]));
  return gap;
}

}  // namespace

void ClosedFamilyOptions::validate() const {
  if (!(tol > 0 && tol <= 0.1)) throw std::invalid_argument("tol: must be in (0, 0.1], got " + std::to_string(tol));
}

JointAxes joint_axes(const Chain& chain) {
  JointAxes g;
  KDL::Frame F = KDL::Frame::Identity();
  for (const KDL::Segment& seg : chain.kdl().segments) {
    const KDL::Joint& joint = seg.getJoint();
    if (joint.getType() != KDL::Joint::Fixed) {
      g.axis.push_back(vec(F.M * joint.JointAxis()).normalized());
      g.point.push_back(vec(F * joint.JointOrigin()));
      g.prismatic.push_back(joint.getType() == KDL::Joint::TransAxis || joint.getType() == KDL::Joint::TransX ||
                            joint.getType() == KDL::Joint::TransY || joint.getType() == KDL::Joint::TransZ);
    }
    const KDL::Frame tip = seg.pose(0.0);
    g.size += vec(tip.p).norm();
    F = F * tip;
  }
  const Vector zero = Vector::Zero(chain.dof());
  chain.fk(zero.data(), g.tool);
  g.size += (g.tool.p - vec(F.p)).norm();  // a tool the chain applies after its segments
  return g;
}

ClosedFamily closed_family(const Chain& chain, const ClosedFamilyOptions& options) {
  return closed_family(joint_axes(chain), options);
}

ClosedFamily closed_family(const JointAxes& g, const ClosedFamilyOptions& options) {
  options.validate();
  ClosedFamily f;
  f.name = "none";
  const int n = static_cast<int>(g.axis.size());
  f.tol_distance = options.tol * std::max(g.size, 1e-300);
  for (int i = 0; i + 1 < n; ++i) {
    if (line_angle(g.axis[i], g.axis[i + 1]) <= options.tol) f.parallel.emplace_back(i + 1, i + 2);
    else if (line_distance(g, i, i + 1) <= f.tol_distance) f.meet.emplace_back(i + 1, i + 2);
  }
  if (n != 6 || std::any_of(g.prismatic.begin(), g.prismatic.end(), [](bool p) { return p; })) {
    f.reason = "6 revolute joints needed: the chain has " + std::to_string(n) + " joints" +
               (std::count(g.prismatic.begin(), g.prismatic.end(), true) ? ", some prismatic" : "");
    return f;
  }
  const bool first_two = line_angle(g.axis[0], g.axis[1]) > options.tol;  // axis 1 not parallel to axis 2
  // The UR family: axes 2, 3, 4 parallel, axes 5 and 6 meet (axis 5 not parallel to them).
  const double par234 = parallel_gap(g, 1, 3);
  Eigen::Vector3d c56;
  const bool meet56 = line_angle(g.axis[4], g.axis[5]) > options.tol &&
                      line_distance(g, 4, 5, &c56) <= f.tol_distance;
  if (par234 <= options.tol && meet56 && first_two && line_angle(g.axis[1], g.axis[4]) > options.tol) {
    f.kind = FamilyKind::ThreeParallel, f.name = "three parallel axes 2, 3, 4", f.center = c56;
    return f;
  }
  Eigen::Vector3d c456;
  const double wrist = wrist_gap(g, 3, c456);
  const double par23 = parallel_gap(g, 1, 2);
  if (wrist <= f.tol_distance && par23 <= options.tol && first_two) {
    f.kind = FamilyKind::SphericalWrist, f.name = "spherical wrist, axes 2, 3 parallel", f.center = c456;
    return f;
  }
  std::string why;
  if (wrist <= f.tol_distance) why = "spherical wrist, but " + axes_text({1, 2}) + " are not parallel: " + degrees(par23);
  else why = axes_text({3, 4, 5}) + " do not meet: " + (std::isinf(wrist) ? "axes 4, 5 parallel" : mm(wrist));
  if (par234 <= options.tol) why += "; " + axes_text({1, 2, 3}) + " are parallel, but axes 5, 6 do not meet";
  else why += "; " + axes_text({1, 2, 3}) + " are not parallel: " + degrees(par234);
  if (!first_two) why += "; axes 1, 2 are parallel";
  f.reason = why;
  return f;
}

}  // namespace robokin
