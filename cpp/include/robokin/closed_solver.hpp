// The closed-form inverse kinematics of one arm, its geometry read once. The solver is chosen from
// the joint axes at q = 0, whatever describes the chain:
//   the UR layout (ur_arm): ik_ur's closed form;
//   a spherical wrist in the ortho-parallel layout (spherical_arm: PUMA, ABB IRB, KUKA KR):
//     ik_spherical's;
//   any other arm closed_family recognises (with a 7-joint chain's joint held): the subproblems'
//     (closed_solve).
// Each layout's own form runs in vectorised stages; all three give the same solutions and labels.
// Nothing changes during a call: one solver may serve every thread.
#pragma once

#include "robokin/closed_solve.hpp"
#include "robokin/ik_closed.hpp"

#include <optional>
#include <string>

namespace robokin {

class ClosedSolver {
 public:
  // Throws std::invalid_argument as closed_arm does when the arm has no closed form, and
  // ("locked: ...") when the held value is outside the joint's limits. The chain must outlive the
  // solver.
  ClosedSolver(const Chain& chain, JointLimits limits, const ClosedFamilyOptions& options = {},
               const std::optional<HeldJoint>& held = std::nullopt);

  // The solver, or none when the arm has no closed form (the arm read once, no exception for it);
  // throws for a bad held joint as the constructor does.
  static std::optional<ClosedSolver> find(const Chain& chain, JointLimits limits,
                                          const ClosedFamilyOptions& options = {},
                                          const std::optional<HeldJoint>& held = std::nullopt);

  ClosedFormSolutions solve(const Rigid& T) const;

  // solve on many frames, as closed_solve_batch: q_out (count, 8, dof()), NaN rows where a slot has
  // no solution.
  void solve_batch(const Rigid* targets, long count, double* q_out, bool* within_limits, bool* singular,
                   Progress* progress = nullptr) const;

  // The decomposition solved, by closed_family's name.
  std::string family() const;
  const Chain& chain() const { return *chain_; }
  const JointLimits& limits() const { return limits_; }
  const ClosedFamilyOptions& options() const { return options_; }
  const std::optional<HeldJoint>& held() const { return arm_.axes.held; }

 private:
  ClosedSolver(const Chain& chain, JointLimits limits, const ClosedFamilyOptions& options,
               const std::optional<HeldJoint>& held, bool required);
  bool solvable() const { return ur_ || spherical_ || arm_.family.kind != FamilyKind::None; }

  const Chain* chain_;
  JointLimits limits_;
  ClosedFamilyOptions options_;
  std::optional<URArm> ur_;
  std::optional<SphericalArm> spherical_;
  ClosedArm arm_;  // read only when neither layout holds
};

}  // namespace robokin
