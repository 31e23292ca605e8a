// Numerical inverse kinematics: Gauss-Newton, Levenberg-Marquardt, Newton-Raphson (damped
// pseudoinverse) and Halley (Lloyd, Irani, Ahmadi, T-RO 2022), with joint limits handled by an
// active set (a joint that would cross its limit stops on it and the others re-solve the step,
// so no joint sticks), revolute angles wrapped by 2 pi into wide limits, and seeded random restarts.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/task.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace robokin {

enum class IkMethod { LM, GN, NR, Halley };

// Names of the methods: "lm" | "gn" | "nr" | "halley" (parse throws std::invalid_argument("method: ...")).
void parse(const std::string& name, IkMethod& method);
const char* name_of(IkMethod method);

// The one source of the default damping (IkOptions::damping unset selects it): lm 1e-1 (initial mu
// relative to max diag(J^T J)), nr 1e-6 and halley 1e-9 (lambda of the damped pseudoinverse), gn 0
// (unused: gn has its own hair of regularisation).
double default_damping(IkMethod method);

// The most restarts a solve accepts (validate() rejects more); `timeout` bounds the time.
constexpr int kMaxRestarts = 1000000;

// The time budget of a solve given neither restarts nor a timeout (seconds of CPU time).
constexpr double kDefaultIkTimeout = 5e-3;

// IkOptions::stall_window when unset: the longer window spares an attempt that may still converge
// when the restart after it is a random guess; a closed-form restart solves at once, so a crawling
// attempt is dropped sooner (benchmarks/bench_ik_latency.py measures both).
constexpr int kStallWindow = 6, kStallWindowClosed = 3;

// The options of a solve: the one place the defaults are written (the bindings bind these fields
// one by one and show the resolved defaults to Python as robokin.IK_DEFAULTS). By default a solve
// restarts from random configurations within the limits until it succeeds or its time budget
// (kDefaultIkTimeout above) runs out: a reachable target is solved (the rate on the catalogue's arms
// is measured by benchmarks/bench_ik_defaults.py); an unreachable one costs the whole budget.
struct IkOptions {
  IkMethod method = IkMethod::LM;
  std::optional<Task> task;  // unset: the chain's natural_task (task.hpp)
  double tol_p = 1e-9;     // position error (m): norm of the task's translational rows
  double tol_r = 1e-9;     // orientation error (rad): rotation angle (pose) or |phi error| (xyphi)
  int max_iter = 100;      // iterations per attempt
  // Extra attempts, in [0, kMaxRestarts]: first from the closed-form solutions of a pose target
  // within the limits (a 6R arm whose geometry closed_family recognises), then from the chain's
  // stored configurations nearest the target (ik_starts.hpp), then random ones within the limits.
  // Unset: as many as the time budget allows.
  std::optional<int> restarts;
  // Seconds of the solving thread's CPU time for the whole solve (every attempt), so that a busy
  // machine does not cut a search short (the wall time may then be longer). Unset:
  // kDefaultIkTimeout when restarts is unset too, no budget when restarts is given.
  std::optional<double> timeout;
  // lambda of the damped pseudoinverse (nr, halley) / initial mu relative to max diag(J^T J) (lm).
  // Unset: default_damping(method).
  std::optional<double> damping;
  // With restarts left, an attempt whose cost |e|^2 has not halved over this many iterations is
  // dropped for a restart (a crawling attempt costs more than a fresh start); 0: never dropped.
  // Unset: kStallWindowClosed for a pose target on an arm with a closed form (its restart starts
  // from an exact solution), kStallWindow otherwise.
  std::optional<int> stall_window;

  // Every option, its Python keyword and its doc, in order: the bindings bind exactly these (an
  // option added above and listed here reaches robokin.ik, ik_batch, IKSolver and IKOptions).
  template <class Visit>
  static void fields(Visit&& field) {
    field("method", &IkOptions::method, "'lm', 'gn', 'nr' or 'halley' (robokin.ik's module docstring).");
    field("task", &IkOptions::task,
          "Which part of the tool pose is solved for: 'pose', 'position', 'xy' or 'xyphi'; None: the chain's "
          "natural task ('pose' for arms of six joints or more, 'position' for fewer, 'xyphi' / 'xy' for planar arms).");
    field("tol_p", &IkOptions::tol_p, "Position tolerance (m).");
    field("tol_r", &IkOptions::tol_r,
          "Orientation tolerance (rad): the rotation angle between the frames (pose), the planar angle (xyphi); "
          "unused for the other tasks.");
    field("max_iter", &IkOptions::max_iter, "Iterations per attempt.");
    field("restarts", &IkOptions::restarts,
          "Extra attempts when an attempt fails, at most 1,000,000, stopping at the first success: for a pose "
          "target on a 6R arm with a closed form (robokin.closed.family), first from its closed-form solutions "
          "within the limits, nearest q0 first; then 8 from the chain's stored configurations (1,024 drawn once "
          "per chain) whose tools are nearest the target; the rest from random configurations drawn uniformly "
          "within the limits (revolute joints without limits: [-pi, pi]). None: as many as the time budget allows. An int: at most that many, and no time budget unless timeout is given "
          "(on an unreachable target they all run).");
    field("timeout", &IkOptions::timeout,
          "Time budget in seconds for all the attempts (checked every few iterations), counted in the solving "
          "thread's CPU time: a busy machine does not cut a search short (the wall time is then longer). None: "
          "IK_DEFAULTS['timeout'] (5 ms) when restarts is None, no budget when restarts is an int. An unreachable "
          "target costs the whole budget.");
    field("damping", &IkOptions::damping,
          "lm: initial damping relative to max diag(J^T J) (default 1e-1); nr: lambda of the damped pseudoinverse "
          "(default 1e-6); halley: the same lambda (default 1e-9); unused by gn. None: the method's default.");
    field("stall_window", &IkOptions::stall_window,
          "With restarts left, an attempt whose squared error has not halved over this many iterations is dropped "
          "for a restart; 0: never dropped. None: 3 for a pose target on an arm with a closed form (its restarts "
          "start from the closed-form solutions, which solve at once), 6 otherwise.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
  // The values a solve runs with.
  int max_restarts() const { return restarts ? *restarts : kMaxRestarts; }
  double budget() const { return timeout ? *timeout : (restarts ? 0.0 : kDefaultIkTimeout); }  // 0: none
  double damping_or_default() const { return damping ? *damping : default_damping(method); }
  Task task_for(const Chain& chain) const { return task ? *task : natural_task(chain); }
  int stall_window_for(const Chain& chain, Task resolved_task) const;
  // A path warm-starts each target from the previous solution: a random restart could land on
  // another branch (a jump of the joints between neighbouring points), so unless restarts are given
  // it does not restart (and has no budget unless a timeout is given).
  IkOptions for_path() const;
};

struct IkResult {
  Vector q;
  bool success = false;
  int iterations = 0;  // saturates at INT_MAX
  int attempts = 0;
  double error_p = 0.0, error_r = 0.0;

  // The fields Python reads, with their docs, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("success", &IkResult::success, "True when FK of q meets tol_p and tol_r (checked after wrapping and clamping).");
    field("iterations", &IkResult::iterations, "Iterations over every attempt.");
    field("attempts", &IkResult::attempts, "1 + the random restarts used.");
    field("error_p", &IkResult::error_p, "Position error at q (m).");
    field("error_r", &IkResult::error_r, "Orientation error at q (rad); 0 for tasks without one.");
    field("q", &IkResult::q, "(dof,) joints, the solution or the best point found (within the limits).");
  }
};

// sum_j a_j dJ/dq_j for the 6 x n geometric Jacobian J6 of chain at some q (Halley's H a).
void hessian_times(const Chain& chain, const Matrix6X& J6, const Vector& a, Matrix6X& out);

// One solver per thread: it owns its workspace (no allocation per iteration).
class IkSolver {
 public:
  IkSolver(const Chain& chain, const IkOptions& options);
  // Re-targets the solver (the workspace is kept when the sizes match): the chain must outlive use.
  void reset(const Chain& chain, const IkOptions& options);

  // Solves from q0; restarts draw from a generator seeded with `seed`. A long solve (many
  // iterations or restarts) reports to `progress` and stops (Interrupted) when it asks.
  IkResult solve(const Target& target, const double* q0, std::uint64_t seed, Progress* progress = nullptr);

  // Errors (position, orientation) of the tool at q for the target, as used for success.
  void errors(const Target& target, const double* q, double& error_p, double& error_r) const;

 private:
  class Budget;    // the time budget: the thread's CPU time (ik_numeric.cpp)
  struct Attempt;  // the state of one attempt between iterations (ik_numeric.cpp)
  enum class Step { Moved, Solved, Stuck };
  // One attempt from q; with may_stall, it gives up early when the error stops decreasing.
  bool attempt(const Target& target, Vector& q, int& iterations, int budget, Budget& clock, bool may_stall,
               Progress* progress);
  // One iteration of each method from q (its Jacobian J_ and error e_ current).
  Step lm_step(const Target& target, Vector& q, Attempt& a);
  Step gn_step(const Target& target, Vector& q, Attempt& a);
  Step newton_step(const Target& target, Vector& q, Attempt& a);  // nr, halley
  void take_trial(Vector& q, double cost_t, Attempt& a);
  double evaluate(const Target& target, const Vector& q, Eigen::MatrixXd& J, Vector& e, double& ep, double& er);
  void errors_of(const Target& target, const Rigid& T, double* e, double& ep, double& er) const;
  void select_rows(const Matrix6X& J6, Eigen::MatrixXd& J) const;
  bool met(double ep, double er) const;
  // Leaves in qt_ the point reached by a step from q through the joint limits, in dq_ the step.
  // `solve(J, r, dq)` maps a Jacobian (frozen joints' columns zeroed) and a residual to a step.
  template <class Solve>
  void constrained_step(const Vector& q, const Eigen::MatrixXd& J, const Vector& e, Solve solve);
  void normal_solve(const Eigen::MatrixXd& J, const Vector& r, double mu, double rel, Vector& dq);
  void damped_pinv(const Eigen::MatrixXd& J, const Vector& r, Vector& dq);
  bool fit(int i, double& v) const;  // wraps a joint value by 2 pi into its limits; false if outside
  double clamp(int i, double v) const;  // the finite point of joint i's limits nearest to v
  void finalise(const Target& target, IkResult& r) const;

  const Chain* chain_ = nullptr;
  IkOptions opt_;
  // opt_ resolved: the task, restarts, time budget (0: none), damping, tol_r (inf for tasks without
  // orientation).
  Task task_ = Task::Pose;
  int restarts_ = 0, stall_window_ = kStallWindow;
  double timeout_ = 0.0, damping_ = 0.0, tol_r_ = 0.0;
  int n_ = -1, m_ = -1;
  // workspace: sized once, no allocation per iteration
  Matrix6X J6_, HA_;
  Eigen::MatrixXd J_, Jt_, Jw_, M_;
  Vector e_, et_, r_, dq_, a_, qt_, qb_;
  std::vector<bool> frozen_;
  Rigid T_;
};

// What ik_batch found, one row per target.
struct IkBatchResult {
  RowMatrix q;  // count x dof
  Eigen::Array<bool, Eigen::Dynamic, 1> success;
  Eigen::ArrayXi iterations, attempts;
  Vector error_p, error_r;

  template <class Visit>
  static void fields(Visit&& field) {
    field("q", &IkBatchResult::q, "(N, dof) joints.");
    field("success", &IkBatchResult::success, "(N,) verified successes.");
    field("iterations", &IkBatchResult::iterations, "(N,) iterations.");
    field("attempts", &IkBatchResult::attempts, "(N,) attempts (1 + restarts used).");
    field("error_p", &IkBatchResult::error_p, "(N,) position errors (m).");
    field("error_r", &IkBatchResult::error_r, "(N,) orientation errors (rad).");
  }
};

// Solves each target; `q0` holds one start per target (stride dof) or one for all (stride 0).
// path: each target starts from the previous solution (sequential, options.for_path()); otherwise
// targets are solved in parallel on every core with seeds seed + k. The caller releases the GIL.
IkBatchResult ik_batch(const Chain& chain, const IkOptions& options, const Target* targets, long count,
                       const double* q0, long q0_stride, bool path, std::uint64_t seed,
                       Progress* progress = nullptr);

}  // namespace robokin
