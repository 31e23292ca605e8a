// 3-RRR path planning with parallel-singularity avoidance (the 3-RRR project, section 2.2.3): the
// orientation leaves its nominal value only where the path comes near a parallel singularity.
#pragma once

#include "robokin/rrr3.hpp"

namespace robokin {

struct RRR3PlanOptions {
  double phi = 0;            // nominal orientation (rad)
  Mode mode = kDefaultMode;    // the one working mode used along the whole path
  bool avoid = true;         // false: every pose at the nominal orientation
  double max_step = 0.01;    // largest orientation change between consecutive path points (rad)
  double margin = kNearDistance;  // wanted distance to parallel singularities (RRR3::distance)
  double serial_margin = kSerialMargin;  // smallest |det B| / l1^3 allowed (never near a serial singularity)
  double span = 1.0;         // largest departure from the nominal orientation (rad)
  double resolution = 0.005;  // orientation grid step (rad), at most max_step
  double smoothing = 10.0;   // weight of (phi_k - phi_{k-1})^2 against (phi_k - phi)^2
  bool closed = false;       // the path is a loop (its last point joins its first): the plan joins up too

  // Every option, its Python keyword and its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("phi", &RRR3PlanOptions::phi, "Nominal orientation (rad).");
    field("mode", &RRR3PlanOptions::mode, "The working mode used along the whole path.");
    field("avoid", &RRR3PlanOptions::avoid, "False: every pose at the nominal orientation.");
    field("max_step", &RRR3PlanOptions::max_step, "Largest orientation change between consecutive points (rad).");
    field("margin", &RRR3PlanOptions::margin, "Wanted distance to parallel singularities (RRR3Singularity.distance).");
    field("serial_margin", &RRR3PlanOptions::serial_margin, "Smallest |det B| / l1^3 allowed.");
    field("span", &RRR3PlanOptions::span, "Largest departure from the nominal orientation (rad), in [0, pi].");
    field("resolution", &RRR3PlanOptions::resolution, "Orientation grid step (rad), at most max_step.");
    field("smoothing", &RRR3PlanOptions::smoothing, "Weight of (phi_k - phi_{k-1})^2 against (phi_k - phi)^2.");
    field("closed", &RRR3PlanOptions::closed,
          "The points are a loop (the last joins the first): the plan joins up too (feasible checks the join).");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
};

struct RRR3Plan {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> poses, alpha;
  Eigen::VectorXd det_a_norm, det_b_norm, distance;
  int sign = 0;  // 0 when none could be chosen
  bool feasible = false;

  // The fields Python reads, with their docs, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("poses", &RRR3Plan::poses, "(K, 3) poses (x, y, phi).");
    field("alpha", &RRR3Plan::alpha, "(K, 3) actuated angles, NaN rows where unreachable (feasible is then False).");
    field("det_a_norm", &RRR3Plan::det_a_norm, "det A / platform_radius along the path, NaN where unreachable.");
    field("det_b_norm", &RRR3Plan::det_b_norm, "det B / l1^3 along the path, NaN where unreachable.");
    field("distance", &RRR3Plan::distance,
          "Distance to parallel singularities (inverse condition number of A) along the path, NaN where\n"
          "unreachable.");
    field("sign", &RRR3Plan::sign, "The sign of det A kept along the path.");
    field("feasible", &RRR3Plan::feasible,
          "Every pose reachable, clear of serial singularities, at distance >= margin, one sign of det A,\n"
          "orientation steps <= max_step (for a closed path the step back to the first pose too).");
  }
};

// The pose sequence for count points (count x 2, row-major). With avoidance the orientation
// sequence minimises sum (phi_k - phi)^2 + smoothing (phi_k - phi_{k-1})^2 over a grid of
// orientations (dynamic programming, so the answer is global and does not chatter), subject to:
// reachable in the mode, |det B| / l1^3 >= serial_margin, det A of the sign it has at the first
// point, |phi_k - phi_{k-1}| <= max_step. A distance to parallel singularities below margin is
// penalised heavily rather than forbidden, so a path always comes back; `feasible` tells.
//
// closed (with avoidance, more than one point): the path is a loop, and an open plan's ends need
// not meet. The loop is cut where it is clearest of parallel singularities at the nominal
// orientation (among the points with det A of the first point's sign there): the orientation is
// at the nominal one at both ends of the cut, so the plan of the loop rolled to start at the cut,
// rolled back, joins up. That plan is returned when it is feasible and its join (last pose to
// first) is at most max_step; else the plan of the path as given (its `feasible` then says
// whether it joins).
RRR3Plan plan_path(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& options,
                   Progress* progress = nullptr);

}  // namespace robokin
