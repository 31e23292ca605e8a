#include "robokin/reach.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>

#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

void check_reach_options(const Chain& chain, const ReachOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0))
      throw std::invalid_argument(std::string(name) + ": must be a positive finite number");
  };
  if (o.max_iter < 1) throw std::invalid_argument("max_iter: must be at least 1");
  positive(o.tol, "tol");
  positive(o.gain, "gain");
  positive(o.dt, "dt");
  if (!(std::isfinite(o.damping) && o.damping >= 0))
    throw std::invalid_argument("damping: must be a finite number >= 0");
  if (o.nullspace_weights.size() != 0) {
    if (o.nullspace_weights.size() != chain.dof())
      throw std::invalid_argument("nullspace: expected " + std::to_string(chain.dof()) +
                                  " gains, got " + std::to_string(o.nullspace_weights.size()));
    if (!o.nullspace_weights.allFinite())
      throw std::invalid_argument("nullspace: gains must be finite");
    for (int i = 0; i < chain.dof(); ++i)
      if (o.nullspace_weights(i) != 0 && !(std::isfinite(chain.lower()(i)) && std::isfinite(chain.upper()(i))))
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

Reacher::Reacher(const Chain& chain, Task task, const ReachOptions& options)
    : chain_(chain), task_(task), opt_(options), m_(task_rows(task)), n_(chain.dof()) {
  check_reach_options(chain, options);
  qbar_ = 0.5 * (chain.lower() + chain.upper());
  for (int i = 0; i < n_; ++i)
    if (!std::isfinite(qbar_(i))) qbar_(i) = 0.0;  // unlimited joints have zero weight
  J6_.resize(6, n_);
  J_.resize(m_, n_);
  JJt_.resize(m_, m_);
  e_.resize(m_);
  dq_.resize(n_);
  h_.resize(n_);
  correction_.resize(n_);
}

void Reacher::min_norm_solve(const TaskVector& rhs, Vector& out) {
  JJt_.noalias() = J_ * J_.transpose();
  JJt_.diagonal().array() += opt_.damping * opt_.damping;
  const Eigen::LLT<TaskSquare> llt(JJt_);
  const auto d = llt.matrixLLT().diagonal();
  if (llt.info() == Eigen::Success && d.minCoeff() > 1e-9 * std::max(1.0, d.maxCoeff())) {
    out.noalias() = J_.transpose() * llt.solve(rhs);
  } else {
    out = Eigen::MatrixXd(J_).completeOrthogonalDecomposition().solve(Eigen::VectorXd(rhs));
  }
}

ReachResult Reacher::reach(const Target& target, const Vector& q0) {
  ReachResult r;
  r.q = q0;
  const bool use_nullspace = opt_.nullspace_weights.size() != 0;
  chain_.fk(r.q.data(), T_);
  task_error(target, T_, e_.data());
  do {
    chain_.fk_jacobian(r.q.data(), T_, J6_.data());
    task_jacobian(task_, J6_, J_);
    // Seed: dp = d (p_target - p) / dt; dq_M = J^p dp; q = Saturation(q + dt dq_M).
    min_norm_solve((opt_.gain / opt_.dt) * e_, dq_);
    if (use_nullspace && r.iterations == 0) {
      // The homogeneous term dq_H = (1 - J^p J) h moves the tool only at second order, so adding
      // it on every iteration leaves a residual of order |dt dq_H|^2 that never drops below tol.
      // It is applied on the first iteration of each Reach only: the following iterations are the
      // seed's minimum-norm corrections, which remove that residual.
      h_ = opt_.nullspace_weights.cwiseProduct(qbar_ - r.q);
      min_norm_solve(J_ * h_, correction_);
      dq_ += h_ - correction_;
    }
    dq_ *= opt_.dt;
    if (!dq_.allFinite()) break;  // an absurd gain or target: stop at the last finite joints
    r.q += dq_;
    if (opt_.saturate) r.q = r.q.cwiseMax(chain_.lower()).cwiseMin(chain_.upper());
    chain_.fk(r.q.data(), T_);
    task_error(target, T_, e_.data());
    ++r.iterations;
    r.error = e_.norm();
  } while (r.iterations < opt_.max_iter && !(r.error < opt_.tol));
  r.error = e_.norm();
  r.converged = r.error < opt_.tol;
  return r;
}

void Reacher::track(const Target* targets, long count, const Vector& q0, double* q_out,
                    double* err_out, bool* converged_out, int* iterations_out) {
  Vector q = q0;
  for (long k = 0; k < count; ++k) {
    ReachResult r = reach(targets[k], q);
    q = r.q;
    Eigen::Map<Vector>(q_out + k * n_, n_) = q;
    err_out[k] = r.error;
    converged_out[k] = r.converged;
    iterations_out[k] = r.iterations;
  }
}

}  // namespace robokin
