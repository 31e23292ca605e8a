// Numerical inverse kinematics: LM, GN, NR and Halley with joint limits and seeded restarts.
#include "robokin/ik.hpp"
#include "robokin/limits.hpp"
#include "robokin/parallel.hpp"

#include "ik_starts.hpp"
#include "linalg.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace robokin {
namespace {

// LM: the most the damping shrinks after a good step (Nielsen uses 1/3; faster end-game here).
constexpr double kMuShrink = 0.1;

// The first restarts start from the closed-form solutions of a pose target within the limits
// (when the chain's geometry has a closed form), nearest the seed first, then from the chain's
// stored configurations whose tools are nearest the target (ik_starts.hpp); the rest from random
// configurations.
constexpr int kNearStarts = 8;

double wall_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double thread_cpu_s() {
  timespec ts;
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return wall_s();
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

// The time budget (IkOptions::timeout) is the solving thread's CPU time: a thread descheduled on a
// busy machine (other processes, more threads than cores) does not see its search cut short, as a
// wall-clock budget did on a loaded machine. The thread's CPU clock costs a system call, so a solve
// that ends within the first 1 % of its budget by the wall clock (most solves of a reachable
// target) never reads it. The CPU clock starts at the first check past that point, charged with
// that 1 %: the CPU time before the check before it is at most its wall time, under 1 %, so the
// charge errs by at most the few iterations between two checks (and never by a spell of being
// descheduled, which charging the wall time would count). After that the CPU clock is read only
// once the wall clock says the budget may be spent.
class IkSolver::Budget {
 public:
  explicit Budget(double seconds) : seconds_(seconds) {
    if (seconds_ > 0) check_at_ = wall_s() + kGrace * seconds_;
  }
  bool spent() {
    if (!(seconds_ > 0)) return false;
    const double now = wall_s();
    if (now < check_at_) return false;
    const double cpu = thread_cpu_s();
    if (!cpu_started_) {
      cpu0_ = cpu - kGrace * seconds_;
      cpu_started_ = true;
    }
    const double left = seconds_ - (cpu - cpu0_);
    if (!(left > 0)) return true;
    check_at_ = now + left;
    return false;
  }

 private:
  static constexpr double kGrace = 0.01;
  double seconds_, cpu0_ = 0.0, check_at_ = 0.0;
  bool cpu_started_ = false;
};

void parse(const std::string& name, IkMethod& method) {
  if (name == "lm") method = IkMethod::LM;
  else if (name == "gn") method = IkMethod::GN;
  else if (name == "nr") method = IkMethod::NR;
  else if (name == "halley") method = IkMethod::Halley;
  else throw std::invalid_argument("method: expected one of 'lm', 'gn', 'nr', 'halley', got '" + name + "'");
}

const char* name_of(IkMethod method) {
  switch (method) {
    case IkMethod::LM: return "lm";
    case IkMethod::GN: return "gn";
    case IkMethod::NR: return "nr";
    case IkMethod::Halley: return "halley";
  }
  return "?";
}

double default_damping(IkMethod method) {
  switch (method) {
    case IkMethod::LM: return 1e-1;
    case IkMethod::GN: return 0.0;
    case IkMethod::NR: return 1e-6;
    case IkMethod::Halley: return 1e-9;
  }
  return 0.0;
}

void IkOptions::validate() const {
  if (!(tol_p > 0) || !std::isfinite(tol_p)) throw std::invalid_argument("tol_p: must be a positive number");
  if (!(tol_r > 0) || !std::isfinite(tol_r)) throw std::invalid_argument("tol_r: must be a positive number");
  if (max_iter < 1) throw std::invalid_argument("max_iter: must be at least 1");
  if (stall_window && *stall_window < 0)
    throw std::invalid_argument("stall_window: must be None or >= 0 (0: never drop an attempt)");
  if (restarts && *restarts < 0) throw std::invalid_argument("restarts: must be >= 0");
  if (restarts && *restarts > kMaxRestarts)
    throw std::invalid_argument("restarts: must be at most " + std::to_string(kMaxRestarts) +
                                " (use timeout to bound the time)");
  if (timeout && !(*timeout > 0 && std::isfinite(*timeout)))
    throw std::invalid_argument("timeout: must be None or a positive number of seconds");
  if (damping && !(*damping > 0 && std::isfinite(*damping)))
    throw std::invalid_argument("damping: must be None or a positive number");
}

int IkOptions::stall_window_for(const Chain& chain, Task resolved_task) const {
  if (stall_window) return *stall_window;
  return resolved_task == Task::Pose && chain.ik_starts().closed_form() ? kStallWindowClosed : kStallWindow;
}

IkOptions IkOptions::for_path() const {
  IkOptions o = *this;
  if (!restarts) {
    o.restarts = 0;
    if (!timeout) o.timeout = 0.0;
  }
  return o;
}

IkSolver::IkSolver(const Chain& chain, const IkOptions& options) { reset(chain, options); }

void IkSolver::reset(const Chain& chain, const IkOptions& options) {
  chain_ = &chain;
  opt_ = options;
  restarts_ = options.max_restarts();
  timeout_ = options.budget();
  damping_ = options.damping_or_default();
  task_ = options.task_for(chain);
  tol_r_ = task_ == Task::Pose || task_ == Task::XYPhi ? options.tol_r : INFINITY;
  stall_window_ = options.stall_window_for(chain, task_);
  const int n = chain.dof(), m = task_rows(task_);
  if (n == n_ && m == m_) return;  // the workspace fits already
  n_ = n;
  m_ = m;
  J6_.resize(6, n_);
  HA_.resize(6, n_);
  J_.resize(m_, n_);
  Jt_.resize(m_, n_);
  Jw_.resize(m_, n_);
  M_.resize(m_, n_);
  e_.resize(m_);
  et_.resize(m_);
  r_.resize(m_);
  dq_.resize(n_);
  a_.resize(n_);
  qt_.resize(n_);
  qb_.resize(n_);
  frozen_.assign(n_, false);
}

// Joint value v brought within the limits of joint i (fit_into_limits: by 2 pi for a revolute).
bool IkSolver::fit(int i, double& v) const {
  return fit_into_limits(v, chain_->lower()(i), chain_->upper()(i), !chain_->prismatic(i));
}

double IkSolver::clamp(int i, double v) const { return nearest_in_limits(v, chain_->lower()(i), chain_->upper()(i)); }

void IkSolver::errors_of(const Target& target, const Rigid& T, double* e, double& ep, double& er) const {
  task_error(target, T, e);
  task_error_norms(task_, e, ep, er);
}

void IkSolver::errors(const Target& target, const double* q, double& ep, double& er) const {
  Rigid T;
  chain_->fk(q, T);
  double e[6];
  errors_of(target, T, e, ep, er);
}

// FK (+ Jacobian rows of the task) and the error at q, into (J, e, ep, er); returns the cost |e|^2.
double IkSolver::evaluate(const Target& target, const Vector& q, Eigen::MatrixXd& J, Vector& e, double& ep,
                          double& er) {
  if (m_ == 6) {  // every row: the Jacobian is written where it is used (J is 6 x n, column-major)
    chain_->fk_jacobian(q.data(), T_, J.data());
  } else {
    chain_->fk_jacobian(q.data(), T_, J6_.data());
    select_rows(J6_, J);
  }
  errors_of(target, T_, e.data(), ep, er);
  return e.squaredNorm();
}

void IkSolver::select_rows(const Matrix6X& J6, Eigen::MatrixXd& J) const {
  if (m_ == 6) {
    J = J6;
    return;
  }
  const int* rows = task_row_indices(task_);
  for (int r = 0; r < m_; ++r) J.row(r) = J6.row(rows[r]);
}

bool IkSolver::met(double ep, double er) const { return ep < opt_.tol_p && er < tol_r_; }

// The active set: solve for a step; a joint that would leave its limits (after wrapping) stops on
// the limit and the step is solved again for the others with the residual it leaves. A joint
// frozen here is free again at the next iteration: nothing sticks.
template <class Solve>
void IkSolver::constrained_step(const Vector& q, const Eigen::MatrixXd& J, const Vector& e, Solve solve) {
  std::fill(frozen_.begin(), frozen_.end(), false);
  // The step is solved from J and e themselves until a joint is frozen; from then on from the
  // copies Jw_ and r_ that freezing changes.
  const Eigen::MatrixXd* Jp = &J;
  const Vector* rp = &e;
  for (int pass = 0; pass <= n_; ++pass) {
    solve(*Jp, *rp, dq_);
    bool changed = false;
    for (int i = 0; i < n_; ++i) {
      if (frozen_[i]) continue;
      double v = q(i) + dq_(i);
      if (!std::isfinite(v)) v = q(i), dq_(i) = 0;
      if (fit(i, v)) {
        qt_(i) = v;
        continue;
      }
      const double lim = clamp(i, v);
      if (Jp == &J) {
        Jw_ = J;
        r_ = e;
        Jp = &Jw_;
        rp = &r_;
      }
      frozen_[i] = true;
      qt_(i) = lim;
      r_ -= J.col(i) * (lim - q(i));
      Jw_.col(i).setZero();
      changed = true;
    }
    if (!changed) break;
  }
  for (int i = 0; i < n_; ++i)
    if (frozen_[i]) dq_(i) = qt_(i) - q(i);
}

namespace {

// dq = (J^T J + s I)^-1 J^T r = J^T (J J^T + s I)^-1 r, from the smaller of the two systems: K x K
// with K = min(rows, joints) <= 6 (fixed when 6: unrolled), solved by ldlt_in_place (linalg.hpp); when it
// is not positive definite (J rank-deficient and s ~ 0), the system's least-squares solution.
template <int K, class JM>
void normal_step(const JM& J, const Vector& r, double s, Vector& dq) {
  using Small = Eigen::Matrix<double, K, K, 0, 6, 6>;
  using SmallVector = Eigen::Matrix<double, K, 1, 0, 6, 1>;
  const bool wide = J.cols() > J.rows();
  const int k = wide ? static_cast<int>(J.rows()) : static_cast<int>(J.cols());
  Small A(k, k);
  SmallVector y;
  // The lower half only (ldlt_in_place reads no more): the dot products of J's rows (J J^T) or
  // columns (J^T J), 21 of 36 for a 6 x 6 system.
  if (wide) {
    for (int j = 0; j < k; ++j)
      for (int i = j; i < k; ++i) A(i, j) = J.row(i).dot(J.row(j));
    y = r;
  } else {
    for (int j = 0; j < k; ++j)
      for (int i = j; i < k; ++i) A(i, j) = J.col(i).dot(J.col(j));
    y.noalias() = J.transpose() * r;
  }
  A.diagonal().array() += s;
  double dmin, dmax;
  if (ldlt_in_place(A, dmin, dmax)) {
    ldlt_solve_in_place(A, y);
  } else {  // rare: the system formed again (the factorisation overwrote it), solved by a COD
    Small A0;
    if (wide) A0.noalias() = J * J.transpose();
    else A0.noalias() = J.transpose() * J;
    A0.diagonal().array() += s;
    y = Eigen::MatrixXd(A0).completeOrthogonalDecomposition().solve(Eigen::VectorXd(y));
  }
  if (wide) dq.noalias() = J.transpose() * y;
  else dq = y;
}

}  // namespace

// dq = (J^T J + (mu + rel max diag(J^T J)) I)^-1 J^T r, the damped normal equations (max diag(J^T J)
// is the largest squared column norm of J).
void IkSolver::normal_solve(const Eigen::MatrixXd& J, const Vector& r, double mu, double rel, Vector& dq) {
  const double s = mu + (rel > 0 ? rel * J.colwise().squaredNorm().maxCoeff() : 0.0);
  if (m_ == 6 && n_ == 6) return normal_step<6>(Eigen::Map<const Eigen::Matrix<double, 6, 6>>(J.data()), r, s, dq);
  if (m_ == 6 && n_ > 6)
    return normal_step<6>(Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>(J.data(), 6, n_), r, s, dq);
  normal_step<Eigen::Dynamic>(J, r, s, dq);
}

// dq = J^T (J J^T + lambda^2 I)^-1 r = (J^T J + lambda^2 I)^-1 J^T r, the damped least-squares
// step: with fewer joints than task rows (J J^T singular by its shape) from the joints' normal
// equations, else the minimum-norm step (min_norm_solve, linalg.hpp, with its singular fallback)
// for the task's fixed number of rows.
void IkSolver::damped_pinv(const Eigen::MatrixXd& J, const Vector& r, Vector& dq) {
  if (m_ > n_) return normal_solve(J, r, damping_ * damping_, 0.0, dq);
  const auto solve = [&](auto rows) {
    constexpr int M = decltype(rows)::value;
    const Eigen::Map<const Eigen::Matrix<double, M, Eigen::Dynamic>> Jm(J.data(), M, n_);
    const Eigen::Matrix<double, M, 1> rhs = r.head<M>();
    min_norm_solve<M>(Jm, rhs, damping_, dq);
  };
  switch (m_) {
    case 6: return solve(std::integral_constant<int, 6>());
    case 3: return solve(std::integral_constant<int, 3>());
    default: return solve(std::integral_constant<int, 2>());
  }
}

// Column k of sum_j a_j dJ/dq_j (the kinematic Hessian applied to a), from the Jacobian's columns:
// revolute k: [W_k x Jv_k + w_k x V_k ; W_k x w_k] with W_k = sum_{j<=k} a_j w_j and
// V_k = sum_{j>k} a_j Jv_j; prismatic k: [W_k x z_k ; 0].
void hessian_times(const Chain& chain, const Matrix6X& J6, const Vector& a, Matrix6X& out) {
  const int n = chain.dof();
  out.resize(6, n);
  Eigen::Vector3d V = Eigen::Vector3d::Zero();
  for (int j = 0; j < n; ++j) V += a(j) * J6.col(j).head<3>();
  Eigen::Vector3d W = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d Jv = J6.col(k).head<3>(), w = J6.col(k).tail<3>();
    V -= a(k) * Jv;  // now the sum over j > k
    if (chain.prismatic(k)) {
      out.col(k).head<3>() = W.cross(Jv);
      out.col(k).tail<3>().setZero();
    } else {
      W += a(k) * w;
      out.col(k).head<3>() = W.cross(Jv) + w.cross(V);
      out.col(k).tail<3>() = W.cross(w);
    }
  }
}

// The state of one attempt between its iterations: the cost |e|^2 at q, the lowest cost seen
// (NR, Halley), LM's damping mu and its growth factor nu.
struct IkSolver::Attempt {
  double cost = 0.0, best_cost = 0.0, mu = 0.0, nu = 2.0;
};

// q moves to the trial point qt_ (with its Jacobian and error).
void IkSolver::take_trial(Vector& q, double cost_t, Attempt& a) {
  q.swap(qt_);
  J_.swap(Jt_);
  e_.swap(et_);
  a.cost = cost_t;
}

// Levenberg-Marquardt: the damped normal equations, a step kept only when it decreases the cost,
// the damping updated from the gain ratio of the actual to the predicted decrease (Nielsen).
IkSolver::Step IkSolver::lm_step(const Target& target, Vector& q, Attempt& a) {
  constrained_step(q, J_, e_, [&](const Eigen::MatrixXd& J, const Vector& r, Vector& dq) {
    normal_solve(J, r, a.mu, 0.0, dq);
  });
  double ept, ert;
  const double cost_t = evaluate(target, qt_, Jt_, et_, ept, ert);
  r_ = e_;
  r_.noalias() -= J_ * dq_;
  const double predicted = a.cost - r_.squaredNorm();
  const double rho = predicted > 0 ? (a.cost - cost_t) / predicted : -1.0;
  if (cost_t < a.cost && rho > 0) {
    take_trial(q, cost_t, a);
    if (met(ept, ert)) return Step::Solved;
    const double t = 2 * rho - 1;
    a.mu *= std::max(kMuShrink, 1.0 - t * t * t);
    a.nu = 2;
    return Step::Moved;
  }
  a.mu *= a.nu;
  a.nu *= 2;
  // mu beyond all scale: a local minimum, nothing decreases the error.
  return a.mu > 1e20 || !std::isfinite(a.mu) ? Step::Stuck : Step::Moved;
}

// Gauss-Newton: the normal equations with a hair of regularisation for a singular J, and a
// backtracking line search on the direction down to 1/2048 of the step (beyond: a local minimum).
IkSolver::Step IkSolver::gn_step(const Target& target, Vector& q, Attempt& a) {
  constrained_step(q, J_, e_, [&](const Eigen::MatrixXd& J, const Vector& r, Vector& dq) {
    normal_solve(J, r, 1e-12, 1e-12, dq);
  });
  a_ = dq_;
  double alpha = 1.0;
  for (int ls = 0; ls < 12; ++ls, alpha *= 0.5) {
    for (int i = 0; i < n_; ++i) {
      double v = q(i) + alpha * a_(i);
      if (!fit(i, v)) v = clamp(i, v);
      qt_(i) = v;
    }
    double ept, ert;
    const double cost_t = evaluate(target, qt_, Jt_, et_, ept, ert);
    if (cost_t < a.cost) {
      take_trial(q, cost_t, a);
      return met(ept, ert) ? Step::Solved : Step::Moved;
    }
  }
  return Step::Stuck;
}

// Newton-Raphson (the damped pseudoinverse step) and Halley (the Newton step a, then the
// correction: solve (J + 1/2 H a) b = e; the Newton step when the free correction is not finite or
// more than twice as long: J + 1/2 H a is then near singular, and a step through the limits solved
// from it would be decided by rounding). Every step is taken; the lowest-cost point seen is kept
// in qb_.
IkSolver::Step IkSolver::newton_step(const Target& target, Vector& q, Attempt& a) {
  const auto pinv = [&](const Eigen::MatrixXd& J, const Vector& r, Vector& dq) { damped_pinv(J, r, dq); };
  bool newton = true;
  if (opt_.method == IkMethod::Halley) {
    damped_pinv(J_, e_, a_);
    if (m_ == 6) J6_ = J_;  // evaluate wrote the 6 rows into J_ alone
    hessian_times(*chain_, J6_, a_, HA_);  // J6_ is the Jacobian at q: the last evaluation was there
    select_rows(HA_, M_);
    M_ = J_ + 0.5 * M_;
    damped_pinv(M_, e_, dq_);
    newton = !dq_.allFinite() || dq_.norm() > 2.0 * a_.norm() + 1e-12;
    if (!newton) constrained_step(q, M_, e_, pinv);
  }
  if (newton) constrained_step(q, J_, e_, pinv);
  if (!(dq_.lpNorm<Eigen::Infinity>() >= 1e-15)) return Step::Stuck;  // stalled (or not finite)
  double ept, ert;
  const double cost_t = evaluate(target, qt_, Jt_, et_, ept, ert);
  if (!std::isfinite(cost_t)) return Step::Stuck;  // no step out of a non-finite pose
  take_trial(q, cost_t, a);
  if (met(ept, ert)) return Step::Solved;
  if (a.cost < a.best_cost) {
    qb_ = q;
    a.best_cost = a.cost;
  }
  return Step::Moved;
}

// One attempt from q (within limits) for at most `budget` iterations of the method's step; q is
// left at the best point. LM and GN accept only decreasing steps; NR and Halley take every step
// (they may climb out of a basin), so the lowest-cost point seen is restored when the attempt ends.
bool IkSolver::attempt(const Target& target, Vector& q, int& iterations, int budget, Budget& clock,
                       bool may_stall, Progress* progress) {
  double ep, er;
  Attempt a;
  a.cost = evaluate(target, q, J_, e_, ep, er);
  if (met(ep, er)) return true;
  qb_ = q;
  a.best_cost = a.cost;
  const auto give_up = [&]() {
    if (a.best_cost < a.cost || !std::isfinite(a.cost)) q = qb_;
    return false;
  };
  if (opt_.method == IkMethod::LM) a.mu = damping_ * std::max(1e-12, J_.colwise().squaredNorm().maxCoeff());
  double window_cost = a.cost;
  for (int it = 0; it < budget; ++it) {
    if ((it & 3) == 3 && clock.spent()) return give_up();
    if ((it & 255) == 255) report(progress, it, budget);
    if (may_stall && stall_window_ > 0 && it > 0 && it % stall_window_ == 0) {
      if (!(a.cost <= 0.5 * window_cost)) return give_up();  // crawling: a restart does better
      window_cost = a.cost;
    }
    if (iterations < std::numeric_limits<int>::max()) ++iterations;
    Step step;
    switch (opt_.method) {
      case IkMethod::LM: step = lm_step(target, q, a); break;
      case IkMethod::GN: step = gn_step(target, q, a); break;
      default: step = newton_step(target, q, a); break;  // NR, Halley
    }
    if (step == Step::Solved) return true;
    if (step == Step::Stuck) return give_up();
  }
  return give_up();
}

IkResult IkSolver::solve(const Target& target, const double* q0, std::uint64_t seed, Progress* progress) {
  IkResult r;
  Budget clock(timeout_);
  Vector q = Eigen::Map<const Vector>(q0, n_);
  for (int i = 0; i < n_; ++i)
    if (!fit(i, q(i))) q(i) = clamp(i, q(i));
  Vector best = q;
  double best_cost = std::numeric_limits<double>::infinity();
  std::optional<std::mt19937_64> rng;  // seeded at the first random restart: a solve without one seeds none
  int near[kNearStarts], closed = 0;
  double closed_q[ClosedFormSolutions::kMaxSolutions * ClosedFormSolutions::kMaxDof];
  for (int k = 0; k <= restarts_; ++k) {
    if (k > 0) {
      if (clock.spent()) break;
      const IkStarts& starts = chain_->ik_starts();
      if (k == 1) closed = starts.closed(*chain_, target, q0, closed_q);
      if (k <= closed) {
        q = Eigen::Map<const Vector>(closed_q + (k - 1) * n_, n_);
      } else if (k <= closed + kNearStarts) {
        if (k == closed + 1) starts.nearest(*chain_, target, kNearStarts, near);
        q = Eigen::Map<const Vector>(starts.q(*chain_, near[k - 1 - closed]), n_);
      } else {
        if (!rng) rng.emplace(seed);
        random_configuration(*chain_, *rng, q.data());
      }
    }
    ++r.attempts;
    report(progress, k, restarts_ + 1);
    PartProgress this_attempt(progress, k, restarts_ + 1);
    if (attempt(target, q, r.iterations, opt_.max_iter, clock, k < restarts_, progress ? &this_attempt : nullptr)) {
      best = q;
      break;
    }
    double ep, er;
    errors(target, q.data(), ep, er);
    const double c = ep * ep + er * er;
    if (c < best_cost) best = q, best_cost = c;
  }
  r.q = best;
  finalise(target, r);
  return r;
}

// Success is decided here, on the returned q: angles wrapped into their limits (nearest to 0 when a
// joint spans more than 2 pi), clamped, then FK and the tolerances.
void IkSolver::finalise(const Target& target, IkResult& r) const {
  for (int i = 0; i < n_; ++i) {
    double& v = r.q(i);
    if (!settle_into_limits(v, chain_->lower()(i), chain_->upper()(i), !chain_->prismatic(i))) v = clamp(i, v);
  }
  errors(target, r.q.data(), r.error_p, r.error_r);
  r.success = r.q.allFinite() && std::isfinite(r.error_p) && std::isfinite(r.error_r) && met(r.error_p, r.error_r);
}

IkBatchResult ik_batch(const Chain& chain, const IkOptions& options, const Target* targets, long count,
                       const double* q0, long q0_stride, bool path, std::uint64_t seed, Progress* progress) {
  const int n = chain.dof();
  IkBatchResult r;
  r.q.resize(count, n);
  r.success.resize(count);
  r.iterations.resize(count);
  r.attempts.resize(count);
  r.error_p.resize(count);
  r.error_r.resize(count);
  auto store = [&](long k, const IkResult& one) {
    r.q.row(k) = one.q.transpose();
    r.success(k) = one.success;
    r.iterations(k) = one.iterations;
    r.attempts(k) = one.attempts;
    r.error_p(k) = one.error_p;
    r.error_r(k) = one.error_r;
  };
  if (path) {
    IkSolver solver(chain, options.for_path());
    for (long k = 0; k < count; ++k) {
      report(progress, k, count);
      const double* start = k == 0 ? q0 : r.q.row(k - 1).data();
      store(k, solver.solve(targets[k], start, seed + static_cast<std::uint64_t>(k)));
    }
    return r;
  }
  parallel_for(count, 16, [&](long begin, long end) {
    IkSolver solver(chain, options);
    for (long k = begin; k < end; ++k)
      store(k, solver.solve(targets[k], q0 + k * q0_stride, seed + static_cast<std::uint64_t>(k)));
  }, progress);
  return r;
}

}  // namespace robokin
