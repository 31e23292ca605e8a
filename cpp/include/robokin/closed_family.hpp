// The geometry of a serial arm read from its chain at the zero configuration (any source: DH,
// modified DH, URDF, joints and frames), and the decomposition its axes allow: which consecutive
// joint axes meet or are parallel, and whether the closed form of closed_solve.hpp covers it.
#pragma once

#include "robokin/chain.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace robokin {

// The options of closed_family (and of the closed forms built on it).
struct ClosedFamilyOptions {
  double tol = 1e-6;  // relative: distances within tol x the arm's size, angles within tol rad

  template <class Visit>
  static void fields(Visit&& field) {
    field("tol", &ClosedFamilyOptions::tol,
          "Two axes meet when they pass within tol x the arm's size (the sum of the chain's fixed "
          "translations at the zero configuration), are parallel when their directions differ by "
          "less than tol rad; in (0, 0.1].");
  }
  // Throws std::invalid_argument("tol: ...") unless 0 < tol <= 0.1.
  void validate() const;
};

// A joint held at a value (Python's locked={joint: value}): joint 0-based, as in q.
struct HeldJoint {
  long joint = 0;
  double value = 0;
};

// The joints at the zero configuration, in the base frame: axis[i] (unit, the direction in which
// joint i turns or slides positively) through point[i]; tool, the tool frame; size, the sum of the
// lengths of the chain's fixed translations (the unit of distances). number[i] is joint i's number
// in its chain (1-based: the names of families and reasons use it); held, a joint held at a value,
// whose motion is folded into the axes after it and the tool.
struct JointAxes {
  std::vector<Eigen::Vector3d> axis, point;
  std::vector<bool> prismatic;
  std::vector<int> number;
  Rigid tool;
  double size = 0;
  std::optional<HeldJoint> held;
};
JointAxes joint_axes(const Chain& chain);

// The axes that remain when joint held.joint is held at held.value: E_1 .. E_j(value) .. E_n T0
// = E_1 .. E_{j-1} E'_{j+1} .. E'_n T0' with E'_k = E_j E_k E_j^-1 (axis k moved by E_j) and
// T0' = E_j T0. Throws std::invalid_argument("locked: ...") for a joint out of range, a value that
// is not finite, or a joint already held.
JointAxes locked_axes(const JointAxes& axes, const HeldJoint& held);
// joint_axes of a 7-joint chain with one joint held, the 6 others free; the chain's own axes when
// none is. Throws std::invalid_argument("locked: ...") for a chain without 7 joints (holding one
// must leave 6), then as locked_axes.
JointAxes joint_axes(const Chain& chain, const std::optional<HeldJoint>& held);

// The chain read from the tool to the base: G = E_1(q1) .. E_n(qn) (G = T T0^-1) gives
// G^-1 = E_n(-qn) .. E_1(-q1), the axes in reverse order with their directions negated, solved for
// G^-1 with an identity tool (joint k of the reversed axes is joint n + 1 - k, with the same value).
JointAxes reversed_axes(const JointAxes& axes);

// The closed-form families of a 6R: none; a spherical wrist (axes 4, 5, 6 meet in a point) with
// axes 2 and 3 parallel; three parallel axes 2, 3, 4 with axes 5 and 6 meeting (the UR family); a
// spherical wrist with axes 1 and 2 meeting (axis 3 passing through neither that point nor the
// wrist's: the iiwa or the Gen3 with a shoulder or elbow joint held); a spherical wrist with axes
// 2 and 3 meeting after axis 1 (axis 1 not through that point, axis 3 not through the wrist's: the
// Panda with its elbow held, read from the tool); three parallel axes 1, 2, 3 with axes 5 and 6
// meeting off axis 4 (the Unitree Z1 with its first joint held). A family may hold for the reversed
// axes (reversed_axes): a spherical shoulder (axes 1, 2, 3 meet). WristMeetAfter and ParallelFirst
// are tried last, after the others from both ends, so that an arm the others read keeps their name.
enum class FamilyKind { None, SphericalWrist, ThreeParallel, WristMeet, WristMeetAfter, ParallelFirst };

struct ClosedFamily {
  FamilyKind kind = FamilyKind::None;
  bool reversed = false;  // the family is the reversed axes' (center, shoulder in base coordinates)
  // "spherical wrist, axes 2, 3 parallel", "three parallel axes 2, 3, 4", "spherical wrist, axes
  // 1, 2 meet", "spherical wrist, axes 2, 3 meet after axis 1" ("spherical shoulder, axes 5, 6
  // meet before axis 7" from the tool: the names say where the lone axis is), "three parallel
  // axes 1, 2, 3 first, axes 5, 6 meet" ("... last, axes 1, 2 meet" from the tool), or "none"
  std::string name;
  std::string reason;  // why none (empty otherwise): "axes 4, 5, 6 do not meet: 3.2 mm apart; ..."
  std::vector<std::pair<int, int>> meet, parallel;  // consecutive axes (joint numbers) that meet / are parallel
  // Where the wrist's axes meet (base frame, q = 0): axes 4, 5, 6, or 5, 6 (ThreeParallel, ParallelFirst).
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  // Where the two axes that meet before the wrist meet: axes 1, 2 (WristMeet), 2, 3 (WristMeetAfter).
  Eigen::Vector3d shoulder = Eigen::Vector3d::Zero();
  double tol_distance = 0;  // the distance tolerance used (m): tol x size
};

// Reads the family of chain's geometry. Throws std::invalid_argument for an invalid options.tol.
// `reversed`, when given, receives reversed_axes(axes) when the family is theirs (read once).
ClosedFamily closed_family(const Chain& chain, const ClosedFamilyOptions& options = {});
ClosedFamily closed_family(const JointAxes& axes, const ClosedFamilyOptions& options = {},
                           JointAxes* reversed = nullptr);

}  // namespace robokin
