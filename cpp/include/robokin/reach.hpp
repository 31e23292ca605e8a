// The "Reach" loop of seed 000 (Algorithm 1): damped steps of the minimum-norm pseudoinverse toward
// a nearby target, saturated at the joint limits, optionally with a null-space term that moves the
// joints away from their limits without moving the tool.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/task.hpp"

#include <vector>

namespace robokin {

struct ReachOptions {
  int max_iter = 25;      // n
  double tol = 1e-5;      // delta, on the norm of the task error
  double gain = 0.75;     // d
  double dt = 0.025;      // dt
  bool saturate = true;   // clamp to the joint limits after every step
  double damping = 0.0;   // lambda: J^T (J J^T + lambda^2 I)^-1; 0 is the seed's pseudoinverse
  // Null-space term h = W (qbar - q). Empty: none. Otherwise the diagonal of W (for the seed's
  // joint-limit avoidance, 1 / (q_max - q_min), 0 where a joint is unlimited).
  Vector nullspace_weights;
};

struct ReachResult {
  Vector q;
  bool converged = false;
  int iterations = 0;
  double error = 0.0;  // norm of the task error at q
};

// Validates options against the chain (sizes, positive finite numbers); throws std::invalid_argument.
void check_reach_options(const Chain& chain, const ReachOptions& options);

// The seed's weights for joint-limit avoidance: 1 / (q_max - q_min), 0 for unlimited joints.
Vector joint_limit_weights(const Chain& chain);

// Reuses its buffers across calls: one per thread, no allocation per iteration.
class Reacher {
 public:
  Reacher(const Chain& chain, Task task, const ReachOptions& options);
  ReachResult reach(const Target& target, const Vector& q0);
  // Follows targets in order, each Reach starting from the previous joints. q_out: count x dof.
  void track(const Target* targets, long count, const Vector& q0, double* q_out, double* err_out,
             bool* converged_out, int* iterations_out);

 private:
  const Chain& chain_;
  Task task_;
  ReachOptions opt_;
  int m_, n_;
  Vector qbar_;
  // Task-sized matrices have at most 6 rows: fixed-capacity storage keeps the loop off the heap.
  using TaskVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  using TaskSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using TaskJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, Eigen::Dynamic>;
  Matrix6X J6_;
  TaskJacobian J_;
  TaskSquare JJt_;
  TaskVector e_;
  Vector dq_, h_, correction_;
  Rigid T_;
  // out <- J^T (J J^T + lambda^2 I)^-1 rhs, the minimum-norm (damped) solution of J out = rhs;
  // the least-squares minimum-norm solution when J J^T is singular and lambda = 0.
  void min_norm_solve(const TaskVector& rhs, Vector& out);
};

}  // namespace robokin
