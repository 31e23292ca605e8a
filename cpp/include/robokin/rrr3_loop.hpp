// 3-RRR loops on one side of the parallel singularities: a closed path planned about the first of
// a list of nominal orientations that keeps det A of a given sign all along (the simulator's
// circle and clover, whichever side the robot is on).
#pragma once

#include "robokin/rrr3_plan.hpp"

#include <limits>
#include <string>
#include <vector>

namespace robokin {

// The nominal orientations a loop tries by default: 0, +-0.05, +-0.1, ... +-1.5 rad (nearest to 0
// first, + before -).
std::vector<double> default_nominals();

struct RRR3LoopOptions {
  int sign = 1;  // the side of the parallel singularities: the sign det A keeps all along (+1 or -1)
  std::vector<double> nominals = default_nominals();  // nominal orientations tried, in order (rad)

  // Every option, its Python keyword and its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("sign", &RRR3LoopOptions::sign, "The sign det A keeps all along (+1 or -1): the side of the parallel singularities.");
    field("nominals", &RRR3LoopOptions::nominals, "Nominal orientations tried in order (rad); default 0, +-0.05, ... +-1.5.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
};

struct RRR3Loop {
  RRR3Plan plan;  // the closed plan about `nominal` (no poses when none was found)
  double nominal = std::numeric_limits<double>::quiet_NaN();  // the nominal orientation used
  bool found = false;
  std::string reason;  // why none was found: "start" or "plan" ("" when found)
};

// The closed plan (RRR3PlanOptions::closed) of the loop's count points (count x 2, row-major)
// about the first nominal orientation that suits, plan's phi replaced by it:
// - with avoidance (plan.avoid): the first nominal at which the first point is reachable with
//   det A of `sign` and whose closed plan is feasible with that sign (every pose clear of
//   parallel singularities by plan.margin, of serial ones by plan.serial_margin, steps and the
//   join at most plan.max_step);
// - without (constant orientation): the first nominal if the first point has det A of `sign`
//   there (the loop may then cross singularities: what turning avoidance off shows; `feasible`
//   tells), else the first nominal whose whole loop keeps `sign`, else the first whose first
//   point has it.
// Not found: reason "start" when at no nominal the first point is reachable with det A of
// `sign`, "plan" when every plan from such a start fails. Throws std::invalid_argument for bad
// options.
RRR3Loop plan_loop(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& plan,
                   const RRR3LoopOptions& loop, Progress* progress = nullptr);

}  // namespace robokin
