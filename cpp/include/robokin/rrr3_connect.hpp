// 3-RRR motion between two poses that never crosses a parallel singularity: a search in
// (x, y, phi) over the poses where det A keeps the start's sign and stays clear of zero.
#pragma once

#include "robokin/rrr3.hpp"
#include "robokin/rrr3_plan.hpp"

#include <stdexcept>
#include <string>

namespace robokin {

struct RRR3ConnectOptions {
  Mode mode = kDefaultMode;     // the working mode, kept along the whole path
  double clearance = kNearDistance;  // smallest distance to parallel singularities (RRR3::distance)
  double serial_margin = kSerialMargin;  // smallest |det B| / l1^3 (never near a serial singularity)
  double max_step = 0.001;    // largest move of E between consecutive poses (m)
  double max_turn = 0.01;     // largest rotation between consecutive poses (rad)
  double resolution = 0.005;  // grid step in x and y (m); in phi it is resolution * max_turn / max_step
  double span = 1.5;          // phi is searched within [min(phi_start, phi_goal) - span, max(...) + span]

  // Every option, its Python keyword and its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("mode", &RRR3ConnectOptions::mode, "The working mode, kept along the path.");
    field("clearance", &RRR3ConnectOptions::clearance, "Smallest distance to parallel singularities, in [0, 1).");
    field("serial_margin", &RRR3ConnectOptions::serial_margin, "Smallest |det B| / l1^3, in [0, 1).");
    field("max_step", &RRR3ConnectOptions::max_step, "Largest move of E between consecutive poses (m).");
    field("max_turn", &RRR3ConnectOptions::max_turn, "Largest rotation between consecutive poses (rad).");
    field("resolution", &RRR3ConnectOptions::resolution, "Grid step in x and y (m), max_step to 1000 max_step.");
    field("span", &RRR3ConnectOptions::span, "Orientations searched beyond the ends' (rad), in [0, pi].");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
};

// No singularity-free path: why, in what() and in reason():
//   "start" / "goal": that pose is unusable itself (a leg cannot reach it, it is on or within the
//       serial margin of a serial singularity, or det A is zero there);
//   "regions": start and goal are in different singularity-free regions of the mode (det A has
//       opposite signs there, or every path of one sign between them comes closer than the
//       clearance within the searched orientations).
class NoRoute : public std::domain_error {
 public:
  NoRoute(std::string reason, const std::string& what) : std::domain_error(what), reason_(std::move(reason)) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

// Poses from start to goal (both included, start first), consecutive poses at most max_step apart
// in (x, y) and max_turn in phi, every pose reachable in the mode with |det B| / l1^3 >=
// min(serial_margin, at start, at goal), det A of the start's sign, and a distance to parallel
// singularities >= min(clearance, at start, at goal) (an end nearer than the clearance is left,
// or reached, by the clearest way the grid offers). Returned as an RRR3Plan (feasible = true,
// sign = the sign kept). A* on a grid of (x, y, phi) anchored at the start, cost = steps of the
// simulator (max(|dE| / max_step, |dphi| / max_turn)), edges checked at the output's spacing,
// then shortened by straight shortcuts that satisfy the same conditions. Throws NoRoute;
// std::invalid_argument for bad options.
RRR3Plan connect(const RRR3& robot, const Pose& start, const Pose& goal, const RRR3ConnectOptions& options,
                 Progress* progress = nullptr);

}  // namespace robokin
