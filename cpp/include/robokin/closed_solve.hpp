// Closed-form inverse kinematics of any 6R arm whose geometry closed_family recognises, from the
// Paden-Kahan subproblems (subproblems.hpp) on the joint axes read at the zero configuration:
//   spherical wrist, axes 2, 3 parallel: q1 (subproblem 4: the wrist centre's height along axis 2),
//     q3 (3: its distance from axis 2), q2 (1), then the wrist (2: q4, q5; 1: q6);
//   three parallel axes 2, 3, 4 (axes 5, 6 meeting): q1 (4), q5 (4: axis 6's tilt from axis 2),
//     q6 (1), q2 + q3 + q4 (1), q3 (3), q2 (1).
// Up to 8 solutions, each checked by the chain's forward model and marked within the limits or
// not, labelled geometrically with the labels of the PUMA and UR closed forms:
//   "shoulder left|right": the wrist point on the -/+ side of x1 = axis 1 x axis 2 (at the
//     solution) from axis 1; the wrist point is where the wrist's axes meet (axes 5, 6 for the
//     three-parallel family);
//   "elbow up|down": the elbow (axis 3) on the side of the line from the shoulder (axis 2) to the
//     wrist (the wrist centre; axis 4 for the three-parallel family) towards axis 1's direction or
//     away from it, in the plane normal to axis 2;
//   "wrist no flip|flip": (a4 x a6) . a5 >= 0 or < 0 for the axes a4, a5, a6 at the solution (the
//     sine of the DH angle of joint 5 of the UR and PUMA tables).
//   spherical wrist, axes 1, 2 meeting (at s; axis 3 through neither s nor the wrist centre c): q3
//     (3: |c - s| fixed by q3 alone), q1, q2 (2), then the wrist; the elbow's label is the turn
//     about axis 3 (a3, at the solution) from the shoulder to the wrist: "up" when
//     a3 . ((s - e) x (c - e)) > 0, e the point of axis 3 nearest s.
//   spherical wrist, axes 2, 3 meeting (at s) after axis 1 (axis 1 not through s, axis 3 not
//     through the wrist centre c): q1 (3: joints 2, 3 fix s, so c seen before joint 1 is |c0 - s|
//     from s, c0 the wrist centre at q = 0), q2, q3 (2), then the wrist. "shoulder left" when c
//     turns positively about axis 1 (a1) from s1, s at the solution: a1 . ((s1 - o) x (c - o)) > 0,
//     o on axis 1; "elbow up" when c turns positively about axis 3 (a3, at the solution) from axis
//     2 (a2): a3 . (a2 x (c - s1)) > 0; where c - s1 lies in the plane of a2 and a3 (the two
//     elbows coincide), "elbow straight" when a3 lies between a2 and c - s1, (a2 x a3) .
//     (a3 x (c - s1)) > 0, "elbow folded" otherwise.
//   three parallel axes 1, 2, 3 (direction a1) first, axes 5, 6 meeting at c (axis 4 parallel to
//     neither, not through c): q4 (4: joints 1 to 3 keep c's height along a1), q5, q6 (2: a1 as the
//     tool sees it, turned back by joint 4, is a1), then joints 1 to 3 as a planar arm moving axis
//     3's point (w, at the solution): q1 (3), q2 (1), q3 from their sum. "shoulder left" when c
//     turns positively about axis 4 (a4, through o4, at the solution) from a1: a4 . (a1 x (c - o4))
//     > 0; "elbow up" when the planar arm turns positively at axis 2 (through o2; o1 on axis 1):
//     a1 . ((o2 - o1) x (w - o2)) > 0 ("elbow straight" where the two coincide and (o2 - o1) .
//     (w - o2) > 0, "folded" otherwise); "wrist no flip" when (a5 x a6) . a1 >= 0.
// A family of the reversed axes (reversed_axes) is solved for the inverse pose and its solutions
// read back; its labels are the reversed arm's (its shoulder is the chain's wrist end).
// Singular cases are flagged: "shoulder singular" (the two q1 coincide), "elbow straight|folded",
// "wrist singular" (axes 4 and 6, or 2 and 6, aligned: a continuum of which q4 = 0, or q6 = 0, is
// returned).
#pragma once

#include "robokin/closed_family.hpp"
#include "robokin/ik_closed.hpp"

namespace robokin {

// An arm's geometry as the closed form reads it, once: the axes of the 6R solved (a 7-joint chain's
// with one joint held: locked_axes, axes.held), its family, and, when the family holds from the
// tool to the base (family.reversed), the reversed axes its solver reads. Made by read_closed_arm
// (or closed_arm), which fill every member.
struct ClosedArm {
  JointAxes axes;
  ClosedFamily family;
  JointAxes solved;  // reversed_axes(axes) when family.reversed, else empty
  double held_cos = 1.0, held_sin = 0.0;  // the held joint's value as a turn (for the FK check)
};

// The arm as the closed form reads it, whatever its family (family.kind None: no closed form, the
// reason in family.reason). Throws std::invalid_argument("locked: ...") as joint_axes does.
ClosedArm read_closed_arm(const Chain& chain, const ClosedFamilyOptions& options = {},
                          const std::optional<HeldJoint>& held = std::nullopt);

// read_closed_arm for an arm that must have a closed form. Throws std::invalid_argument("chain: no
// closed form for this arm (<reason>)") when closed_family finds none ("locked: ..." with a joint
// held), and as read_closed_arm.
ClosedArm closed_arm(const Chain& chain, const ClosedFamilyOptions& options = {},
                     const std::optional<HeldJoint>& held = std::nullopt);

// Every solution of the tool frame T (rows of chain.dof() joints: a held joint's value in its
// place); slot[k] (when given, size 8) is row k's slot as in kURPostures (shoulder left 0 / right 1,
// elbow up 0 / down 1, wrist no flip 0 / flip 1; a singular one's 0).
ClosedFormSolutions closed_solve(const ClosedArm& arm, const Chain& chain, const Rigid& T, const JointLimits& limits,
                                 int* slot = nullptr);

// A batch, as ik_ur_batch (ik_closed.hpp): q_out (count, 8, chain.dof()), NaN rows where a slot has
// none.
void closed_solve_batch(const ClosedArm& arm, const Chain& chain, const Rigid* targets, long count,
                        const JointLimits& limits, double* q_out, bool* within_limits, bool* singular,
                        Progress* progress = nullptr);

}  // namespace robokin
