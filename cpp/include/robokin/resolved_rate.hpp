// Velocity-level inverse kinematics: resolved-rate control with the damped least-squares
// pseudoinverse and the RPR study's null-space term (the same step as the Reach loop, linalg.hpp), and a
// servo loop that follows a sampled Cartesian trajectory with feed-forward and error feedback.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/progress.hpp"
#include "robokin/task.hpp"

#include <optional>

namespace robokin {

// The options of resolved-rate control (rk.resolved_rate's keywords).
struct RateOptions {
  std::optional<Task> task;  // unset: the chain's natural_task (task.hpp)
  double damping = 0.0;      // lambda of J^T (J J^T + lambda^2 I)^-1; 0: the minimum-norm pseudoinverse
  // Null-space term h = diag(gains) (qbar - q) (as ReachOptions, reach.hpp); empty: none. Set from
  // the call's `nullspace` argument, which needs the chain.
  Vector nullspace_gains;

  // Every option Python sets by keyword, its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("task", &RateOptions::task, "'pose', 'position', 'xy' or 'xyphi'; None: the chain's natural task.");
    field("damping", &RateOptions::damping, "lambda of the damped pseudoinverse J^T (J J^T + lambda^2 I)^-1, >= 0.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range or not fitting the chain.
  void validate(const Chain& chain) const;
  Task task_for(const Chain& chain) const { return task ? *task : natural_task(chain); }
};

// The options of the servo loop (rk.servo's keywords): resolved-rate control plus the feedback.
struct ServoOptions : RateOptions {
  double gain = 0.75;    // share of the task error corrected per step (the seed's d)
  bool saturate = true;  // clamp the joints to their limits after every step

  template <class Visit>
  static void fields(Visit&& field) {
    RateOptions::fields(field);
    field("gain", &ServoOptions::gain, "Share of the task error corrected per step, >= 0 (0: feed-forward only).");
    field("saturate", &ServoOptions::saturate, "Clamp the joints to their limits after every step.");
  }

  void validate(const Chain& chain) const;
};

// What the servo loop did, one row per control step.
struct ServoResult {
  Vector t;
  RowMatrix q, qd;  // count x dof
  Vector error_p, error_r;

  // The fields Python reads, with their docs, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("t", &ServoResult::t, "(K,) step times k dt.");
    field("q", &ServoResult::q, "(K, dof) joints at each step (before its velocity is applied).");
    field("qd", &ServoResult::qd, "(K, dof) joint velocities commanded at each step.");
    field("error_p", &ServoResult::error_p, "(K,) position error (m): the norm of the task's translational rows.");
    field("error_r", &ServoResult::error_r,
          "(K,) orientation error (rad): the rotation angle to the target (pose), |phi error| (xyphi), 0 without "
          "orientation.");
  }
};

class RateController {
 public:
  RateController(const Chain& chain, const RateOptions& options);
  // qdot = J^p twist + (1 - J^p J) h at q; twist has task_rows(task) values.
  void joint_velocity(const double* q, const double* twist, double* qdot);

  // Follows targets[0..count) one per period dt: at step k the tool's error e_k toward target k is
  // recorded, then q_{k+1} = q_k + dt qdot_k with qdot_k = J^p (v_k + gain e_k / dt) + null-space
  // term, v_k the feed-forward task velocity from target k to target k + 1 (0 after the last).
  // Validates options and dt (std::invalid_argument naming them); the controller's task is used.
  ServoResult servo(const ServoOptions& options, double dt, const Target* targets, long count, const Vector& q0,
                    Progress* progress = nullptr);

 private:
  template <int M>
  void solve(const double* q, const double* rhs, double* qdot);
  void solve_rows(const double* q, const double* rhs, double* qdot);

  const Chain& chain_;
  RateOptions opt_;
  Task task_;  // opt_.task resolved for the chain
  int m_, n_;
  Vector qbar_, h_, correction_;
  Matrix6X J6_;
  Eigen::MatrixXd J_;
};

}  // namespace robokin
