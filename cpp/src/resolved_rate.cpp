#include "robokin/resolved_rate.hpp"
#include "robokin/reach.hpp"

#include "linalg.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

void RateOptions::validate(const Chain& chain) const { check_damping_and_nullspace(chain, damping, nullspace_gains); }

void ServoOptions::validate(const Chain& chain) const {
  RateOptions::validate(chain);
  if (!(std::isfinite(gain) && gain >= 0)) throw std::invalid_argument("gain: must be a finite number >= 0");
}

RateController::RateController(const Chain& chain, const RateOptions& options)
    : chain_(chain), opt_(options), task_(options.task_for(chain)), m_(task_rows(task_)), n_(chain.dof()) {
  options.validate(chain);
  qbar_ = joint_middles(chain);
  h_.resize(n_);
  correction_.resize(n_);
  J6_.resize(6, n_);
  J_.resize(m_, n_);
}

template <int M>
void RateController::solve(const double* q, const double* rhs_data, double* qdot_data) {
  Eigen::Map<Eigen::Matrix<double, M, Eigen::Dynamic>> J(J_.data(), M, n_);
  const int* rows = task_row_indices(task_);
  for (int r = 0; r < M; ++r) J.row(r) = J6_.row(rows[r]);
  const Eigen::Matrix<double, M, 1> rhs = Eigen::Map<const Eigen::Matrix<double, M, 1>>(rhs_data);
  Eigen::Map<Vector> qdot(qdot_data, n_), h(h_.data(), n_), correction(correction_.data(), n_);
  min_norm_solve<M>(J, rhs, opt_.damping, qdot);
  if (opt_.nullspace_gains.size() != 0) {
    const Eigen::Map<const Vector> gains(opt_.nullspace_gains.data(), n_), qbar(qbar_.data(), n_), qv(q, n_);
    add_nullspace_term<M>(J, opt_.damping, gains, qbar, qv, h, correction, qdot);
  }
}

void RateController::solve_rows(const double* q, const double* rhs, double* qdot) {
  switch (m_) {
    case 2: return solve<2>(q, rhs, qdot);
    case 3: return solve<3>(q, rhs, qdot);
    default: return solve<6>(q, rhs, qdot);
  }
}

void RateController::joint_velocity(const double* q, const double* twist, double* qdot) {
  Rigid T;
  chain_.fk_jacobian(q, T, J6_.data());
  solve_rows(q, twist, qdot);
}

namespace {

// The frame a target stands for (its free coordinates zero): so that the feed-forward velocity
// between two targets is the task error of one toward the other.
Rigid frame_of(const Target& t) {
  Rigid T;
  switch (t.task) {
    case Task::Pose: return t.pose;
    case Task::Position: T.p = t.value; return T;
    case Task::XY: T.p << t.value(0), t.value(1), 0.0; return T;
    case Task::XYPhi:
      T.p << t.value(0), t.value(1), 0.0;
      T.R << std::cos(t.value(2)), -std::sin(t.value(2)), 0, std::sin(t.value(2)), std::cos(t.value(2)), 0, 0, 0, 1;
      return T;
  }
  return T;
}

}  // namespace

ServoResult RateController::servo(const ServoOptions& o, double dt, const Target* targets, long count,
                                  const Vector& q0, Progress* progress) {
  o.validate(chain_);
  if (!(std::isfinite(dt) && dt > 0)) throw std::invalid_argument("dt: must be a positive finite number");
  opt_ = o;
  ServoResult r;
  r.t.resize(count);
  r.q.resize(count, n_);
  r.qd.resize(count, n_);
  r.error_p.resize(count);
  r.error_r.resize(count);
  Vector q = q0;
  double e[6], ff[6], rhs[6];
  Rigid T;
  for (long k = 0; k < count; ++k) {
    if (k % 256 == 0) report(progress, k, count);
    r.t(k) = static_cast<double>(k) * dt;
    chain_.fk_jacobian(q.data(), T, J6_.data());
    task_error(targets[k], T, e);
    task_error_norms(task_, e, r.error_p(k), r.error_r(k));
    if (k + 1 < count) task_error(targets[k + 1], frame_of(targets[k]), ff);
    for (int i = 0; i < m_; ++i) rhs[i] = (k + 1 < count ? ff[i] : 0.0) / dt + o.gain * e[i] / dt;
    double* qdot = r.qd.row(k).data();
    solve_rows(q.data(), rhs, qdot);
    r.q.row(k) = q.transpose();
    const Eigen::Map<const Vector> qd(qdot, n_);
    if (!qd.allFinite() || !(q + dt * qd).allFinite())
      throw std::invalid_argument("poses: the joint velocities are not finite at step " + std::to_string(k) +
                                  " (targets too far away for gain and dt)");
    q += dt * qd;
    if (o.saturate) q = q.cwiseMax(chain_.lower()).cwiseMin(chain_.upper());
  }
  return r;
}

}  // namespace robokin
