#include "robokin/reach.hpp"

#include "linalg.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>
#include <limits>

#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

void ReachOptions::validate(const Chain& chain) const {
  const ReachOptions& o = *this;
  auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0))
      throw std::invalid_argument(std::string(name) + ": must be a positive finite number");
  };
  // One Reach holds the GIL (it is short); 100,000 iterations take well under a second, so Ctrl-C
  // is never kept waiting long.
  if (o.max_iter < 1 || o.max_iter > kMaxReachIterations)
    throw std::invalid_argument("max_iter: must be in [1, " + std::to_string(kMaxReachIterations) + "], got " +
                                std::to_string(o.max_iter));
  positive(o.tol, "tol");
  positive(o.gain, "gain");
  positive(o.dt, "dt");
  check_damping_and_nullspace(chain, o.damping, o.nullspace_gains);
}

void check_damping_and_nullspace(const Chain& chain, double damping, const Vector& gains) {
  if (!(std::isfinite(damping) && damping >= 0))
    throw std::invalid_argument("damping: must be a finite number >= 0");
  if (gains.size() != 0) {
    if (gains.size() != chain.dof())
      throw std::invalid_argument("nullspace: expected " + std::to_string(chain.dof()) +
                                  " gains, got " + std::to_string(gains.size()));
    if (!gains.allFinite())
      throw std::invalid_argument("nullspace: gains must be finite");
    for (int i = 0; i < chain.dof(); ++i)
      if (gains(i) != 0 && !(std::isfinite(chain.lower()(i)) && std::isfinite(chain.upper()(i))))
        throw std::invalid_argument("nullspace: joint " + std::to_string(i) +
                                    " has no finite limits to stay away from; give it a zero gain");
  }
}

Vector joint_limit_weights(const Chain& chain) {
  Vector w(chain.dof());
  for (int i = 0; i < chain.dof(); ++i) {
    const double range = chain.upper()(i) - chain.lower()(i);
    w(i) = (std::isfinite(range) && range > 0) ? 1.0 / range : 0.0;
  }
  return w;
}

Vector joint_limit_gains(const Chain& chain) { return joint_limit_weights(chain).array().square(); }

Vector joint_middles(const Chain& chain) {
  Vector qbar = 0.5 * (chain.lower() + chain.upper());
  for (int i = 0; i < chain.dof(); ++i)
    if (!std::isfinite(qbar(i))) qbar(i) = 0.0;
  return qbar;
}

double joint_limit_cost(const Chain& chain, const double* q) {
  const Vector w = joint_limit_weights(chain), qbar = joint_middles(chain);
  return 0.5 * (w.array() * (qbar - Eigen::Map<const Vector>(q, chain.dof())).array()).square().sum();
}

Reacher::Reacher(const Chain& chain, Task task, const ReachOptions& options)
    : chain_(chain), task_(task), opt_(options), m_(task_rows(task)), n_(chain.dof()) {
  options.validate(chain);
  qbar_ = joint_middles(chain);
  q_.resize(n_);
  J6_.resize(6, n_);
  J_.resize(m_, n_);
  dq_.resize(n_);
  h_.resize(n_);
  correction_.resize(n_);
}

// The loop with M task rows and N joints known at compile time (N = Eigen::Dynamic otherwise):
// fixed-size matrices on the stack, maps over the Reacher's buffers.
template <int M, int N>
int Reacher::run_rows(const Target& target, double& error) {
  using RowsVector = Eigen::Matrix<double, M, 1>;
  using JointVector = Eigen::Matrix<double, N, 1>;
  Eigen::Map<Eigen::Matrix<double, M, N>> J(J_.data(), M, n_);
  Eigen::Map<JointVector> q(q_.data(), n_), dq(dq_.data(), n_), h(h_.data(), n_), correction(correction_.data(), n_);
  const Eigen::Map<const JointVector> lower(chain_.lower().data(), n_), upper(chain_.upper().data(), n_),
      qbar(qbar_.data(), n_);
  Eigen::Map<RowsVector> e(e_);
  const int* rows = task_row_indices(task_);
  const bool use_nullspace = opt_.nullspace_gains.size() != 0;
  const double step = opt_.gain / opt_.dt;
  task_error(target, T_, e_);
  error = safe_norm(e);
  int iterations = 0;
  do {
    for (int r = 0; r < M; ++r) J.row(r) = J6_.row(rows[r]);
    // Seed: dp = d (p_target - p) / dt; dq_M = J^p dp; q = Saturation(q + dt dq_M).
    const RowsVector rhs = step * e;
    min_norm_solve<M>(J, rhs, opt_.damping, dq);
    if (use_nullspace && iterations == 0) {
      // The homogeneous term dq_H = (1 - J^p J) h moves the tool only at second order, so adding
      // it on every iteration leaves a residual of order |dt dq_H|^2 that never drops below tol.
      // It is applied on the first iteration of each Reach only: the following iterations are the
      // seed's minimum-norm corrections, which remove that residual.
      const Eigen::Map<const JointVector> gains(opt_.nullspace_gains.data(), n_);
      add_nullspace_term<M>(J, opt_.damping, gains, qbar, q, h, correction, dq);
    }
    dq *= opt_.dt;
    // An absurd gain or target: stop at the last finite joints (q + dq may overflow too).
    if (!dq.allFinite() || !(q + dq).allFinite()) break;
    q += dq;
    if (opt_.saturate) q = q.cwiseMax(lower).cwiseMin(upper);
    // Pose and Jacobian at the new joints: the error now, the Jacobian for the next iteration.
    chain_.fk_jacobian(q_.data(), T_, J6_.data());
    task_error(target, T_, e_);
    ++iterations;
    error = safe_norm(e);
  } while (iterations < opt_.max_iter && !(error < opt_.tol));
  return iterations;
}

template <int M>
int Reacher::run_joints(const Target& target, double& error) {
  switch (n_) {
    case 3: return run_rows<M, 3>(target, error);
    case 6: return run_rows<M, 6>(target, error);
    default: return run_rows<M, Eigen::Dynamic>(target, error);
  }
}

int Reacher::run(const Target& target, double& error) {
  switch (m_) {
    case 2: return run_joints<2>(target, error);
    case 3: return run_joints<3>(target, error);
    default: return run_joints<6>(target, error);
  }
}

ReachResult Reacher::reach(const Target& target, const Vector& q0) {
  q_ = q0;
  chain_.fk_jacobian(q_.data(), T_, J6_.data());
  ReachResult r;
  r.iterations = run(target, r.error);
  r.converged = r.error < opt_.tol;
  r.q = q_;
  return r;
}

TrackResult Reacher::track(const Target* targets, long count, const Vector& q0, Progress* progress) {
  TrackResult r;
  r.q.resize(count, n_);
  r.error.resize(count);
  r.converged.resize(count);
  r.iterations.resize(count);
  q_ = q0;
  chain_.fk_jacobian(q_.data(), T_, J6_.data());
  // Progress (and Ctrl-C) every 6,400 iterations at most: every 256 points at the default max_iter,
  // every point from max_iter 6,400 on.
  const long every = std::max(1, 6400 / opt_.max_iter);
  for (long k = 0; k < count; ++k) {
    if (k % every == 0) report(progress, k, count);
    double error = 0.0;
    r.iterations(k) = run(targets[k], error);
    r.error(k) = error;
    r.converged(k) = error < opt_.tol;
    r.q.row(k) = q_.transpose();
  }
  return r;
}

}  // namespace robokin
