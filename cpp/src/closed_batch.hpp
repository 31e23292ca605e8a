// The batch loop of the closed forms of 6R arms (ik_ur_batch, closed_solve_batch, also with a
// seventh joint held): targets split over every core; each target's solutions land in the slot of
// their posture (8 rows of dof joints), the slots without a solution NaN and not within limits.
#pragma once

#include "robokin/ik_closed.hpp"
#include "robokin/parallel.hpp"

#include <algorithm>
#include <limits>

namespace robokin {

// solve_one(k, slot) -> ClosedFormSolutions of target k, writing each solution's posture index
// into slot[i].
template <class SolveOne>
void closed_batch(long count, long grain, int dof, const SolveOne& solve_one, double* q_out, bool* within_limits,
                  bool* singular, Progress* progress) {
  parallel_for(
      count, grain,
      [&](long begin, long end) {
        int slot[8];
        for (long k = begin; k < end; ++k) {
          double* row = q_out + 8 * dof * k;
          bool* within = within_limits + 8 * k;
          std::fill(row, row + 8 * dof, std::numeric_limits<double>::quiet_NaN());
          std::fill(within, within + 8, false);
          const ClosedFormSolutions s = solve_one(k, slot);
          for (int i = 0; i < s.count(); ++i) {
            std::copy(s.row(i), s.row(i) + dof, row + dof * slot[i]);
            within[slot[i]] = s.within_limits[i];
          }
          singular[k] = s.singular;
        }
      },
      progress);
}

}  // namespace robokin
