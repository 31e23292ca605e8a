// The 3-RRR inverse model over a batch of poses (rrr3_ik_batch.cpp): RRR3::ik_batch's loop, written
// for the vectoriser.
#pragma once

#include "robokin/progress.hpp"

namespace robokin::kernel {

// The legs of a 3-RRR as the batch loop reads them: base joints o (x, y per leg), platform joints b
// in the effector frame, elbow signs m of the working mode, link lengths l1, l2.
struct RRR3Legs {
  double o[6], b[6], m[3], l1, l2;
};

// out (count, 3): the actuated angles of poses (count, 3) of (x, y, phi), a row of NaN where a leg
// cannot reach; RRR3::ik's bits (the same leg_alpha_args and vmath routines), on every core.
void rrr3_ik_batch(const RRR3Legs& legs, const double* poses, long count, double* out, Progress* progress);

}  // namespace robokin::kernel
