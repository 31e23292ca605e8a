#include "robokin/closed_solver.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

namespace robokin {
namespace {

// The shortest text that reads back as v (as Python's repr writes a float).
std::string shortest(double v) {
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// The held value within the joint's limits (when the chain has limits).
void require_held_within(const std::optional<HeldJoint>& held, const JointLimits& limits) {
  if (!held || limits.lower.size() == 0) return;
  const long i = held->joint;
  if (!(held->value >= limits.lower[i] && held->value <= limits.upper[i]))
    throw std::invalid_argument("locked: q[" + std::to_string(i) + "] = " + shortest(held->value) +
                                " is outside the joint's limits [" + shortest(limits.lower[i]) + ", " +
                                shortest(limits.upper[i]) + "]");
}

}  // namespace

ClosedSolver::ClosedSolver(const Chain& chain, JointLimits limits, const ClosedFamilyOptions& options,
                           const std::optional<HeldJoint>& held)
    : ClosedSolver(chain, std::move(limits), options, held, true) {}

ClosedSolver::ClosedSolver(const Chain& chain, JointLimits limits, const ClosedFamilyOptions& options,
                           const std::optional<HeldJoint>& held, bool required)
    : chain_(&chain), limits_(std::move(limits)), options_(options) {
  // The layouts' own forms take the six joints as they are: a held joint goes to the subproblems.
  if (!held) ur_ = chain.closed_layout().ur, spherical_ = chain.closed_layout().spherical;
  if (!ur_ && !spherical_) arm_ = required ? closed_arm(chain, options, held) : read_closed_arm(chain, options, held);
  if (solvable()) require_held_within(held, limits_);
}

std::optional<ClosedSolver> ClosedSolver::find(const Chain& chain, JointLimits limits,
                                               const ClosedFamilyOptions& options,
                                               const std::optional<HeldJoint>& held) {
  ClosedSolver solver(chain, std::move(limits), options, held, false);
  if (!solver.solvable()) return std::nullopt;
  return solver;
}

ClosedFormSolutions ClosedSolver::solve(const Rigid& T) const {
  if (ur_) return ik_ur(*ur_, *chain_, T, limits_);
  if (spherical_) return ik_spherical(*spherical_, *chain_, T, limits_);
  return closed_solve(arm_, *chain_, T, limits_);
}

void ClosedSolver::solve_batch(const Rigid* targets, long count, double* q_out, bool* within_limits,
                               bool* singular, Progress* progress) const {
  if (ur_) ik_ur_batch(*ur_, *chain_, targets, count, limits_, q_out, within_limits, singular, progress);
  else if (spherical_)
    ik_spherical_batch(*spherical_, *chain_, targets, count, limits_, q_out, within_limits, singular, progress);
  else closed_solve_batch(arm_, *chain_, targets, count, limits_, q_out, within_limits, singular, progress);
}

std::string ClosedSolver::family() const {
  if (ur_) return "three parallel axes 2, 3, 4";
  if (spherical_) return "spherical wrist, axes 2, 3 parallel";
  return arm_.family.name;
}

}  // namespace robokin
