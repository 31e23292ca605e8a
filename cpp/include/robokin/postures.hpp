// Path tracking with the fewest reconfigurations: the dynamic programme of robokin.track_postures
// over the layered graph of each waypoint's inverse solutions (IKLink's objective).
#pragma once

#include "robokin/limits.hpp"

#include <Eigen/Core>

#include <cstdint>
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

// The waypoints k of the joint path q (count rows of n joints, row-major) entered by a
// reconfiguration: some joint i changes from row k - 1 (from q0 for k = 0, when q0 is not null) by
// more than qdot_max[i] * dt (1 + 1e-9), posture_step's change; in order. track_postures counts
// its steps by the same rule, over the waypoint intervals between rows that have solutions.
std::vector<std::int64_t> count_reconfigurations(const double* q, long count, long n, const double* qdot_max, double dt,
                                                 const std::vector<bool>& continuous, const double* q0);

// One waypoint's solutions (count rows of n joints) less their copies: keep (count flags) holds on
// entry the rows found, on return those kept: a row found is dropped when every joint of it is
// within 1e-6 (posture_step's change) of a row kept before it. One solution per posture the IK's
// starts reached, in the order they were found.
void distinct_rows(const double* q, long count, long n, const std::vector<bool>& continuous, bool* keep);

// The plan: the row chosen at each waypoint, the waypoints its rows enter by a reconfiguration,
// its motion, and the joint path.
struct PosturePlan {
  using Indices = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1>;
  using Joints = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  Indices pick;          // (K,): the row of waypoint k's solutions, -1 where it has none
  Indices reconfigured;  // the waypoints entered by a reconfiguration, in order (the optimum's count)
  double motion = 0;     // as the programme summed it
  Joints q;              // (K, n): the picked rows, continuous joints unwrapped (track_postures says how)

  template <class F>
  static void fields(F&& f) {
    f("pick", &PosturePlan::pick, "(K,) the row of each waypoint's solutions chosen, -1 where it has none.");
    f("reconfigured", &PosturePlan::reconfigured, "The waypoints the plan enters by a reconfiguration, in order.");
    f("motion", &PosturePlan::motion, "The sum over the steps of the norm of the joint change (rad).");
    f("q", &PosturePlan::q,
      "(K, n) the joint path of the picked rows, continuous joints shifted by whole turns within the limits, "
      "gaps filled with the joints before them.");
  }
};

// One row per waypoint with solutions minimising first the number of reconfigurations, then the
// motion. A step from row a of waypoint k to row b of waypoint l (the next one with solutions) is a
// reconfiguration when some joint i changes by more than qdot_max[i] * dt * (l - k) * (1 + 1e-9)
// (the gap's duration, a hair of slack for rounding); its motion is the Euclidean norm of the
// change (squares summed over the joints in order). q0 (n joints, or null) is waypoint -1: the step
// to the first waypoint with solutions counts too. Ties: among equal (reconfigurations, motion)
// the lowest row, both for each row's predecessor and for the last waypoint's row.
// The joint path q: the picked rows, each continuous joint shifted by the whole turns that bring it
// nearest the joints before it (q0 for the first) where that stays within limits (lower, upper:
// n values each); a waypoint without solution repeats the joints before it, leading ones the
// first solution's (or q0).
PosturePlan track_postures(const std::vector<PostureLayer>& layers, long n, const double* qdot_max, double dt,
                           const std::vector<bool>& continuous, const double* q0, const JointLimits& limits);

}  // namespace robokin
