// The batch loop of the 6R closed forms (ik_ur_batch, closed_solve_batch): targets split over
// every core; each target's solutions land in the slot of their posture (8 rows of 6 joints), the
// slots without a solution NaN and not within limits.
#pragma once

#include "robokin/ik_closed.hpp"
#include "robokin/parallel.hpp"

#include <algorithm>
#include <limits>

namespace robokin {

// solve_one(k, slot) -> ClosedFormSolutions of target k, writing each solution's posture index
// into slot[i].
template <class SolveOne>
void closed_batch(long count, long grain, const SolveOne& solve_one, double* q_out, bool* within_limits,
                  bool* singular, Progress* progress) {
  parallel_for(
      count, grain,
      [&](long begin, long end) {
        int slot[8];
        for (long k = begin; k < end; ++k) {
          double* row = q_out + 48 * k;
          bool* within = within_limits + 8 * k;
          std::fill(row, row + 48, std::numeric_limits<double>::quiet_NaN());
          std::fill(within, within + 8, false);
          const ClosedFormSolutions s = solve_one(k, slot);
          for (int i = 0; i < s.count(); ++i) {
            std::copy(s.row(i), s.row(i) + 6, row + 6 * slot[i]);
            within[slot[i]] = s.within_limits[i];
          }
          singular[k] = s.singular;
        }
      },
      progress);
}

}  // namespace robokin
