// Path tracking with the fewest reconfigurations: the dynamic programme of robokin.track_postures
// over the layered graph of each waypoint's inverse solutions (IKLink's objective).
#pragma once

#include <vector>

namespace robokin {

// One waypoint's inverse solutions: count rows of n joints, row-major (count may be 0).
struct PostureLayer {
  const double* q = nullptr;
  long count = 0;
};

// The joint change a -> b of joint i: b - a, the short way round on a continuous joint
// (numpy's remainder(b - a + pi, 2 pi) - pi: the sign of the divisor).
double posture_step(double a, double b, bool continuous);

// The plan: pick[k] is the row chosen at waypoint k (-1 where it has no solution); the waypoints
// the chosen rows enter by a reconfiguration, in order (their number is the optimum's), and its
// motion as the programme summed it.
struct PosturePlan {
  std::vector<long> pick;
  std::vector<long> reconfigured;
  double motion = 0;
};

// One row per waypoint with solutions minimising first the number of reconfigurations, then the
// motion. A step from row a of waypoint k to row b of waypoint l (the next one with solutions) is a
// reconfiguration when some joint i changes by more than qdot_max[i] * dt * (l - k) * (1 + 1e-9)
// (the gap's duration, a hair of slack for rounding); its motion is the Euclidean norm of the
// change (squares summed over the joints in order). q0 (n joints, or null) is waypoint -1: the step
// to the first waypoint with solutions counts too. Ties: among equal (reconfigurations, motion)
// the lowest row, both for each row's predecessor and for the last waypoint's row. Allocates the
// back pointers only (one per solution).
PosturePlan track_postures(const std::vector<PostureLayer>& layers, long n, const double* qdot_max, double dt,
                           const std::vector<bool>& continuous, const double* q0);

}  // namespace robokin
