// robokin.closed is bound in two files: ik_closed.cpp (IKSolutions and the free functions) and
// closed_solver.cpp (ClosedSolver). What they share.
#pragma once

#include "arrays.hpp"

#include "robokin/ik_closed.hpp"

#include <vector>

namespace robokin::bind {

// The chain's UR geometry; ValueError (naming what differs) when it has not the UR layout.
URArm ur_arm_arg(const Chain& chain);

// (N, 4, 4) rigid frames; ValueError naming `name` for a wrong shape, a non-finite value or a frame
// that is not a rigid transform.
std::vector<Rigid> rigid_frames(ArrayLike targets, const char* name);

// ik_ur_batch on (N, 4, 4) frames, the GIL released: (q (N, 8, 6), singular (N,), within_limits (N, 8)).
pybind11::tuple ur_batch_with(ArrayLike targets, const Chain& chain, const URArm& arm, const JointLimits& limits);

}  // namespace robokin::bind
