// Velocity-level inverse kinematics: resolved-rate control with the damped least-squares
// pseudoinverse and the RPR study's null-space term (the same step as the Reach loop, linalg.hpp), and a
// servo loop that follows a sampled Cartesian trajectory with feed-forward and error feedback.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/progress.hpp"
#include "robokin/task.hpp"

namespace robokin {

struct RateOptions {
  Task task = Task::Pose;
  double damping = 0.0;     // lambda of J^T (J J^T + lambda^2 I)^-1; 0: the minimum-norm pseudoinverse
  Vector nullspace_gains;  // empty: none; else h = diag(gains) (qbar - q) (ReachOptions, reach.hpp)
};

struct ServoOptions {
  RateOptions rate;
  double dt = 0.01;      // control period (s): one step per target
  double gain = 0.75;    // share of the task error corrected per step (the seed's d)
  bool saturate = true;  // clamp the joints to their limits after every step
};

// Checks sizes and numbers (std::invalid_argument naming the option).
void check_rate_options(const Chain& chain, const RateOptions& options);
void check_servo_options(const Chain& chain, const ServoOptions& options);

class RateController {
 public:
  RateController(const Chain& chain, const RateOptions& options);
  // qdot = J^p twist + (1 - J^p J) h at q; twist has task_rows(task) values.
  void joint_velocity(const double* q, const double* twist, double* qdot);

  // Follows targets[0..count) one per period dt: at step k the tool's error e_k toward target k is
  // recorded (error_p: norm of the translational rows, error_r: rotation angle, or |phi error|
  // for xyphi, 0 without orientation), then q_{k+1} = q_k + dt qdot_k with
  // qdot_k = J^p (v_k + gain e_k / dt) + null-space term, v_k the feed-forward task velocity from
  // target k to target k + 1 (0 after the last). q_out, qdot_out: count x dof.
  void servo(const ServoOptions& options, const Target* targets, long count, const Vector& q0, double* q_out,
             double* qdot_out, double* error_p, double* error_r, Progress* progress = nullptr);

 private:
  template <int M>
  void solve(const double* q, const double* rhs, double* qdot);
  void solve_rows(const double* q, const double* rhs, double* qdot);

  const Chain& chain_;
  RateOptions opt_;
  int m_, n_;
  Vector qbar_, h_, correction_;
  Matrix6X J6_;
  Eigen::MatrixXd J_;
};

}  // namespace robokin
