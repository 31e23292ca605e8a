// A chain's joint axes at the zero configuration and the closed-form family they allow.
#include "robokin/closed_family.hpp"

#include "lines.hpp"

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
  return robokin::line_distance(g.point[i], g.axis[i], g.point[j], g.axis[j], nearest);
}

// "axes 2, 3, 4": the joint numbers of g's axes at the 0-based indices, in increasing order.
std::string axes_text(const JointAxes& g, std::initializer_list<int> axes) {
  std::vector<int> numbers;
  for (int i : axes) numbers.push_back(g.number[i]);
  std::sort(numbers.begin(), numbers.end());
  std::string s = "axes ";
  for (int n : numbers) s += (s.size() > 5 ? ", " : "") + std::to_string(n);
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

// Distance of point x from the line of axis i.
double point_line_distance(const JointAxes& g, int i, const Eigen::Vector3d& x) {
  const Eigen::Vector3d w = x - g.point[i];
  return (w - w.dot(g.axis[i]) * g.axis[i]).norm();
}

// The family of a 6R's axes, read in g's order (the kinds of FamilyKind), its wrist centre and the
// point where the two axes before the wrist meet; `why` says why none holds, in g's joint numbers.
// `late` is set, with `center` (and `shoulder`), when WristMeetAfter or ParallelFirst holds (kind
// stays None unless another family does: those two are taken only when none holds from either end).
struct Reading {
  FamilyKind kind = FamilyKind::None, late = FamilyKind::None;
  Eigen::Vector3d center = Eigen::Vector3d::Zero(), shoulder = Eigen::Vector3d::Zero();
  std::string why;
};

// Axes first, first + 1 (0-based) meet (not parallel) at `shoulder`, the lone axis of 1 .. 3
// does not pass through that point (else axes 1, 2, 3 meet in a point: its distance from the wrist
// centre c is the same for every posture, a continuum of solutions or none), and axis 3 does not
// pass through c (else c is moved by two joints alone); `why` says what fails otherwise.
bool meets_pair(const JointAxes& g, int first, int lone, double tol, double tol_d, const Eigen::Vector3d& c,
                Eigen::Vector3d& shoulder, std::string& why) {
  const std::string pair = axes_text(g, {first, first + 1});
  if (line_angle(g.axis[first], g.axis[first + 1]) <= tol) return why = pair + " are parallel", false;
  const double d = line_distance(g, first, first + 1, &shoulder);
  if (d > tol_d) return why = pair + " do not meet: " + mm(d), false;
  if (point_line_distance(g, lone, shoulder) <= tol_d)
    return why = axes_text(g, {0, 1, 2}) + " meet in a point, as " + axes_text(g, {3, 4, 5}) +
                 " do: the distance between the two points is the same for every posture (a continuum "
                 "of solutions or none)", false;
  if (point_line_distance(g, 2, c) <= tol_d)
    return why = "axis " + std::to_string(g.number[2]) + " passes through the wrist centre", false;
  return true;
}

// Axes 1, 2, 3 parallel (a planar arm: no two of them the same line), axis 4 not parallel to them,
// axes 5, 6 meeting at c56 off axis 4 (else joint 4 does not move c56's height along axis 1, which
// joints 1 to 3 keep: a continuum of solutions or none); `why` says what fails otherwise.
bool parallel_first(const JointAxes& g, double tol, double tol_d, bool meet56, const Eigen::Vector3d& c56,
                    std::string& why) {
  const std::string three = axes_text(g, {0, 1, 2}) + " are parallel, but ";
  if (parallel_gap(g, 0, 2) > tol) return false;  // the reason says so already
  if (line_distance(g, 0, 1) <= tol_d || line_distance(g, 1, 2) <= tol_d)
    return why = three + "two of them are one line", false;
  if (line_angle(g.axis[0], g.axis[3]) <= tol) return why = three + "so is axis " + std::to_string(g.number[3]), false;
  if (!meet56) return why = three + axes_text(g, {4, 5}) + " do not meet", false;
  if (point_line_distance(g, 3, c56) <= tol_d)
    return why = three + "axis " + std::to_string(g.number[3]) + " passes through the point where " +
                 axes_text(g, {4, 5}) + " meet", false;
  return true;
}

Reading read_family(const JointAxes& g, double tol, double tol_d) {
  Reading r;
  const bool first_two = line_angle(g.axis[0], g.axis[1]) > tol;  // axis 1 not parallel to axis 2
  // The UR family: axes 2, 3, 4 parallel, axes 5 and 6 meet (axis 5 not parallel to them).
  const double par234 = parallel_gap(g, 1, 3);
  Eigen::Vector3d c56;
  const bool meet56 = line_angle(g.axis[4], g.axis[5]) > tol && line_distance(g, 4, 5, &c56) <= tol_d;
  if (par234 <= tol && meet56 && first_two && line_angle(g.axis[1], g.axis[4]) > tol) {
    r.kind = FamilyKind::ThreeParallel, r.center = c56;
    return r;
  }
  const double wrist = wrist_gap(g, 3, r.center);
  const double par23 = parallel_gap(g, 1, 2);
  if (wrist <= tol_d && par23 <= tol && first_two) {
    r.kind = FamilyKind::SphericalWrist;
    return r;
  }
  std::string meet_why, after_why;
  if (wrist <= tol_d && meets_pair(g, 0, 2, tol, tol_d, r.center, r.shoulder, meet_why)) {
    r.kind = FamilyKind::WristMeet;
    return r;
  }
  if (wrist <= tol_d && meets_pair(g, 1, 0, tol, tol_d, r.center, r.shoulder, after_why)) {
    r.late = FamilyKind::WristMeetAfter;
    return r;
  }
  std::string first_why;
  if (parallel_first(g, tol, tol_d, meet56, c56, first_why)) {
    r.late = FamilyKind::ParallelFirst, r.center = c56;
    return r;
  }
  std::string& why = r.why;
  if (wrist <= tol_d)
    why = "spherical wrist, but " +
          (par23 > tol ? axes_text(g, {1, 2}) + " are not parallel: " + degrees(par23) + " and " : "") + meet_why +
          (after_why == meet_why ? "" : " and " + after_why);
  else why = axes_text(g, {3, 4, 5}) + " do not meet: " + (std::isinf(wrist) ? axes_text(g, {3, 4}) + " parallel" : mm(wrist));
  if (par234 <= tol) why += "; " + axes_text(g, {1, 2, 3}) + " are parallel, but " + axes_text(g, {4, 5}) + " do not meet";
  else why += "; " + axes_text(g, {1, 2, 3}) + " are not parallel: " + degrees(par234);
  if (!first_two) why += "; " + axes_text(g, {0, 1}) + " are parallel";
  if (!first_why.empty()) why += "; " + first_why;
  return r;
}

// The family's name in the chain's joint numbers: a reversed family's wrist is a shoulder. The
// lone axis of WristMeetAfter is named, before the pair in the chain's order (after it reversed);
// ParallelFirst's parallel axes are the first (last) in the chain's order, unlike ThreeParallel's.
std::string family_name(FamilyKind kind, bool reversed, const JointAxes& g) {
  const std::string end = reversed ? "spherical shoulder, " : "spherical wrist, ";
  switch (kind) {
    case FamilyKind::ThreeParallel: return "three parallel " + axes_text(g, {1, 2, 3});
    case FamilyKind::SphericalWrist: return end + axes_text(g, {1, 2}) + " parallel";
    case FamilyKind::WristMeet: return end + axes_text(g, {0, 1}) + " meet";
    case FamilyKind::WristMeetAfter:
      return end + axes_text(g, {1, 2}) + " meet " + (reversed ? "before" : "after") + " axis " +
             std::to_string(g.number[0]);
    case FamilyKind::ParallelFirst:
      return "three parallel " + axes_text(g, {0, 1, 2}) + (reversed ? " last, " : " first, ") + axes_text(g, {4, 5}) +
             " meet";
    default: return "none";
  }
}

}  // namespace

void ClosedFamilyOptions::validate() const {
  if (!(tol > 0 && tol <= 0.1)) throw std::invalid_argument("tol: must be in (0, 0.1], got " + std::to_string(tol));
}

JointAxes joint_axes(const Chain& chain) {
  JointAxes g;
  const size_t n = static_cast<size_t>(chain.dof());
  g.axis.reserve(n), g.point.reserve(n), g.prismatic.reserve(n), g.number.reserve(n);
  KDL::Frame F = KDL::Frame::Identity();
  for (const KDL::Segment& seg : chain.kdl().segments) {
    const KDL::Joint& joint = seg.getJoint();
    if (joint.getType() != KDL::Joint::Fixed) {
      g.axis.push_back(vec(F.M * joint.JointAxis()).normalized());
      g.point.push_back(vec(F * joint.JointOrigin()));
      g.prismatic.push_back(joint.getType() == KDL::Joint::TransAxis || joint.getType() == KDL::Joint::TransX ||
                            joint.getType() == KDL::Joint::TransY || joint.getType() == KDL::Joint::TransZ);
      g.number.push_back(static_cast<int>(g.number.size()) + 1);
    }
    const KDL::Frame tip = seg.pose(0.0);
    g.size += vec(tip.p).stableNorm();  // stableNorm: lengths beyond 1e154 would overflow a sum of squares
    F = F * tip;
  }
  const Vector zero = Vector::Zero(chain.dof());
  chain.fk(zero.data(), g.tool);
  g.size += (g.tool.p - vec(F.p)).stableNorm();  // a tool the chain applies after its segments
  return g;
}

JointAxes locked_axes(const JointAxes& g, const HeldJoint& held) {
  const int n = static_cast<int>(g.axis.size());
  if (g.held) throw std::invalid_argument("locked: a joint is already held");
  if (held.joint < 0 || held.joint >= n)
    throw std::invalid_argument("locked: joint index " + std::to_string(held.joint) + " out of range for a chain of " +
                                std::to_string(n) + " joints (indices 0 to " + std::to_string(n - 1) + ")");
  if (!std::isfinite(held.value)) throw std::invalid_argument("locked: the held value must be finite");
  const int joint = static_cast<int>(held.joint);
  Rigid E;  // the held joint's motion, in the base frame
  if (g.prismatic[joint]) {
    E.p = held.value * g.axis[joint];
  } else {
    E.R = Eigen::AngleAxisd(held.value, g.axis[joint]).toRotationMatrix();
    E.p = g.point[joint] - E.R * g.point[joint];
  }
  JointAxes out;
  out.size = g.size, out.held = held, out.tool = E * g.tool;
  for (int i = 0; i < n; ++i) {
    if (i == joint) continue;
    out.axis.push_back(i < joint ? g.axis[i] : Eigen::Vector3d(E.R * g.axis[i]));
    out.point.push_back(i < joint ? g.point[i] : Eigen::Vector3d(E.R * g.point[i] + E.p));
    out.prismatic.push_back(g.prismatic[i]);
    out.number.push_back(g.number[i]);
  }
  return out;
}

JointAxes joint_axes(const Chain& chain, const std::optional<HeldJoint>& held) {
  if (!held) return joint_axes(chain);
  if (chain.dof() != 7)
    throw std::invalid_argument("locked: holding a joint needs a chain of 7 joints (the 6 others are solved); "
                                "this one has " + std::to_string(chain.dof()));
  return locked_axes(joint_axes(chain), *held);
}

JointAxes reversed_axes(const JointAxes& g) {
  JointAxes r;
  r.size = g.size, r.held = g.held;
  for (int i = static_cast<int>(g.axis.size()) - 1; i >= 0; --i) {
    r.axis.push_back(-g.axis[i]);
    r.point.push_back(g.point[i]);
    r.prismatic.push_back(g.prismatic[i]);
    r.number.push_back(g.number[i]);
  }
  return r;  // identity tool: the reversed problem is solved for G^-1
}

ClosedFamily closed_family(const Chain& chain, const ClosedFamilyOptions& options) {
  return closed_family(joint_axes(chain), options);
}

ClosedFamily closed_family(const JointAxes& g, const ClosedFamilyOptions& options, JointAxes* reversed) {
  options.validate();
  ClosedFamily f;
  f.name = "none";
  const int n = static_cast<int>(g.axis.size());
  f.tol_distance = options.tol * std::max(g.size, 1e-300);
  for (int i = 0; i + 1 < n; ++i) {
    const std::pair<int, int> pair(g.number[i], g.number[i + 1]);
    if (line_angle(g.axis[i], g.axis[i + 1]) <= options.tol) f.parallel.push_back(pair);
    else if (line_distance(g, i, i + 1) <= f.tol_distance) f.meet.push_back(pair);
  }
  if (n != 6 || std::any_of(g.prismatic.begin(), g.prismatic.end(), [](bool p) { return p; })) {
    f.reason = "6 revolute joints needed: the chain has " + std::to_string(n) + " joints" +
               (std::count(g.prismatic.begin(), g.prismatic.end(), true) ? ", some prismatic" : "") +
               (n == 7 && !g.held ? "; hold one (locked={index: value}) to solve the 6 others" : "");
    return f;
  }
  Reading r = read_family(g, options.tol, f.tol_distance), back;
  JointAxes back_axes;
  if (r.kind == FamilyKind::None) {
    back_axes = reversed_axes(g);
    back = read_family(back_axes, options.tol, f.tol_distance);
  }
  // WristMeetAfter and ParallelFirst last: where another family holds from either end, that one
  // (and its name) is kept.
  if (r.kind == FamilyKind::None && back.kind == FamilyKind::None) {
    if (r.late != FamilyKind::None) r.kind = r.late;
    else back.kind = back.late;
  }
  if (r.kind != FamilyKind::None) {
    f.kind = r.kind, f.center = r.center, f.shoulder = r.shoulder, f.name = family_name(r.kind, false, g);
    return f;
  }
  if (back.kind == FamilyKind::None) {
    f.reason = r.why + "; from the tool: " + back.why.substr(0, back.why.find(';'));
    return f;
  }
  f.kind = back.kind, f.center = back.center, f.shoulder = back.shoulder, f.reversed = true;
  f.name = family_name(back.kind, true, back_axes);
  if (reversed) *reversed = std::move(back_axes);
  return f;
}

}  // namespace robokin
