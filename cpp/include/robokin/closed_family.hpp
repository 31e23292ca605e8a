// The geometry of a serial arm read from its chain at the zero configuration (any source: DH,
// modified DH, URDF, joints and frames), and the decomposition its axes allow: which consecutive
// joint axes meet or are parallel, and whether the closed form of closed_solve.hpp covers it.
#pragma once

#include "robokin/chain.hpp"

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

// The joints at the zero configuration, in the base frame: axis[i] (unit, the direction in which
// joint i turns or slides positively) through point[i]; tool, the tool frame; size, the sum of the
// lengths of the chain's fixed translations (the unit of distances).
struct JointAxes {
  std::vector<Eigen::Vector3d> axis, point;
  std::vector<bool> prismatic;
  Rigid tool;
  double size = 0;
};
JointAxes joint_axes(const Chain& chain);

// The closed-form families: none; a spherical wrist (axes 4, 5, 6 meet in a point) with axes 2 and
// 3 parallel; three parallel axes 2, 3, 4 with axes 5 and 6 meeting (the UR family).
enum class FamilyKind { None, SphericalWrist, ThreeParallel };

struct ClosedFamily {
  FamilyKind kind = FamilyKind::None;
  std::string name;    // "spherical wrist, axes 2, 3 parallel", ..., or "none"
  std::string reason;  // why none (empty otherwise): "axes 4, 5, 6 do not meet: 3.2 mm apart; ..."
  std::vector<std::pair<int, int>> meet, parallel;  // consecutive axes (1-based) that meet / are parallel
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // where the wrist's axes meet (base frame, q = 0)
  double tol_distance = 0;  // the distance tolerance used (m): tol x size
};

// Reads the family of chain's geometry. Throws std::invalid_argument for an invalid options.tol.
ClosedFamily closed_family(const Chain& chain, const ClosedFamilyOptions& options = {});
ClosedFamily closed_family(const JointAxes& axes, const ClosedFamilyOptions& options = {});

}  // namespace robokin
