// The "Reach" loop of the RPR study (Algorithm 1): damped steps of the minimum-norm pseudoinverse toward
// a nearby target, saturated at the joint limits, optionally with a null-space term that moves the
// joints away from their limits without moving the tool.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/task.hpp"

#include <vector>

namespace robokin {

// Iterations one Reach may run at most (max_iter).
constexpr int kMaxReachIterations = 100000;

// The options of one Reach (and of every point of a tracked path): the seed's values by default.
struct ReachOptions {
  int max_iter = 25;      // n
  double tol = 1e-5;      // delta, on the norm of the task error
  double gain = 0.75;     // d
  double dt = 0.025;      // dt
  bool saturate = true;   // clamp to the joint limits after every step
  double damping = 0.0;   // lambda: J^T (J J^T + lambda^2 I)^-1; 0 is the seed's pseudoinverse
  // Null-space term h = G (qbar - q), G = diag(nullspace_gains): -grad z_G for the cost
  // z_G = 1/2 (qbar - q)^T G (qbar - q). Empty: none. joint_limit_gains gives the seed's joint-limit
  // avoidance, G = W^T W (z_G is then the seed's z).
  Vector nullspace_gains;

  // The options Python sets by keyword, with their docs, in order (the bindings bind exactly these;
  // the null-space weights come from rk.reach's `nullspace` argument).
  template <class Visit>
  static void fields(Visit&& field) {
    field("max_iter", &ReachOptions::max_iter, "Iterations at most (the seed's n), in [1, 100000].");
    field("tol", &ReachOptions::tol, "Tolerance on the norm of the task error (the seed's delta; metres for positions).");
    field("gain", &ReachOptions::gain, "The seed's gain d: dp = d (p_target - p) / dt.");
    field("dt", &ReachOptions::dt, "The seed's time step.");
    field("saturate", &ReachOptions::saturate, "Clamp the joints to their limits after every step.");
    field("damping", &ReachOptions::damping,
          "lambda of the damped pseudoinverse J^T (J J^T + lambda^2 I)^-1, for use near singularities.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range or not fitting the chain.
  void validate(const Chain& chain) const;
};

struct ReachResult {
  Vector q;
  bool converged = false;
  int iterations = 0;
  double error = 0.0;

  // The fields Python reads, with their docs, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("converged", &ReachResult::converged, "True when the task error is below tol.");
    field("iterations", &ReachResult::iterations, "Iterations run.");
    field("error", &ReachResult::error, "Norm of the task error at q.");
    field("q", &ReachResult::q, "Joints at the end.");
  }
};

// What tracking a path did, one row per path point.
struct TrackResult {
  RowMatrix q;  // count x dof
  Vector error;
  Eigen::Array<bool, Eigen::Dynamic, 1> converged;
  Eigen::ArrayXi iterations;

  template <class Visit>
  static void fields(Visit&& field) {
    field("q", &TrackResult::q, "(K, dof) joints after each point.");
    field("error", &TrackResult::error, "(K,) task error after each point.");
    field("converged", &TrackResult::converged, "(K,) True where the point was reached within tol.");
    field("iterations", &TrackResult::iterations, "(K,) Reach iterations per point.");
  }
};

// The damping and null-space checks of ReachOptions::validate, shared with resolved-rate control.
void check_damping_and_nullspace(const Chain& chain, double damping, const Vector& nullspace_gains);

// The middle of each joint's range (the seed's qbar); 0 for an unlimited joint (its weight is 0).
Vector joint_middles(const Chain& chain);

// The seed's weights W = diag(1 / (q_max - q_min)) of its joint-limit cost z, 0 for unlimited joints.
Vector joint_limit_weights(const Chain& chain);

// The null-space gains of the seed's joint-limit avoidance: W^T W's diagonal, 1 / (q_max - q_min)^2
// (0 for unlimited joints), so that h = W^T W (qbar - q) = -grad z. The seed writes h = W (qbar - q)
// and calls it -grad z; that is the gradient of another cost, 1/2 (qbar - q)^T W (qbar - q), whose
// minimum on the self-motion set is not z's: along the RPR study's line (the demo) its term levels off
// 4 % above the mean of each point's least z however strong it is made, while the gradient's term
// comes within 0.1 % and nearer as its gain grows (tests/test_reach.py).
Vector joint_limit_gains(const Chain& chain);

// The seed's joint-limit cost z = 1/2 |W (qbar - q)|^2 (eqs. 6-7), W from joint_limit_weights and
// qbar the middle of each limited joint's range.
double joint_limit_cost(const Chain& chain, const double* q);

// Reuses its buffers across calls: one per thread, no allocation per iteration nor per path point.
class Reacher {
 public:
  Reacher(const Chain& chain, Task task, const ReachOptions& options);
  ReachResult reach(const Target& target, const Vector& q0);
  // Follows targets in order, each Reach starting from the previous joints.
  TrackResult track(const Target* targets, long count, const Vector& q0, Progress* progress = nullptr);

 private:
  const Chain& chain_;
  Task task_;
  ReachOptions opt_;
  int m_, n_;
  Vector qbar_;
  // The state of the loop: joints, tool pose and the 6 x n Jacobian at q_ (kept valid from one
  // path point to the next, so that each iteration evaluates the chain once).
  Vector q_;
  Rigid T_;
  Matrix6X J6_;
  Eigen::MatrixXd J_;  // the task's rows, m x n
  Vector dq_, h_, correction_;
  double e_[6];
  // One Reach from q_ toward target (J6_ and T_ valid at q_); returns the iterations run.
  int run(const Target& target, double& error);
  template <int M>
  int run_joints(const Target& target, double& error);
  template <int M, int N>
  int run_rows(const Target& target, double& error);
};

}  // namespace robokin
