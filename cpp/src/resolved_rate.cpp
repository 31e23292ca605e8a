#include "robokin/resolved_rate.hpp"
#include "robokin/reach.hpp"

#include "linalg.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {

void check_rate_options(const Chain& chain, const RateOptions& o) {
  check_damping_and_nullspace(chain, o.damping, o.nullspace_gains);
}

void check_servo_options(const Chain& chain, const ServoOptions& o) {
  check_rate_options(chain, o.rate);
  if (!(std::isfinite(o.dt) && o.dt > 0)) throw std::invalid_argument("dt: must be a positive finite number");
  if (!(std::isfinite(o.gain) && o.gain >= 0)) throw std::invalid_argument("gain: must be a finite number >= 0");
}

RateController::RateController(const Chain& chain, const RateOptions& options)
    : chain_(chain), opt_(options), m_(task_rows(options.task)), n_(chain.dof()) {
  check_rate_options(chain, options);
  qbar_ = joint_middles(chain);
  h_.resize(n_);
  correction_.resize(n_);
  J6_.resize(6, n_);
  J_.resize(m_, n_);
}

template <int M>
void RateController::solve(const double* q, const double* rhs_data, double* qdot_data) {
  Eigen::Map<Eigen::Matrix<double, M, Eigen::Dynamic>> J(J_.data(), M, n_);
  const int* rows = task_row_indices(opt_.task);
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

void RateController::servo(const ServoOptions& o, const Target* targets, long count, const Vector& q0, double* q_out,
                           double* qdot_out, double* error_p, double* error_r, Progress* progress) {
  check_servo_options(chain_, o);
  opt_ = o.rate;
  Vector q = q0;
  double e[6], ff[6], rhs[6];
  Rigid T;
  for (long k = 0; k < count; ++k) {
    if (k % 256 == 0) report(progress, k, count);
    chain_.fk_jacobian(q.data(), T, J6_.data());
    task_error(targets[k], T, e);
    task_error_norms(opt_.task, e, error_p[k], error_r[k]);
    if (k + 1 < count) task_error(targets[k + 1], frame_of(targets[k]), ff);
    for (int r = 0; r < m_; ++r) rhs[r] = (k + 1 < count ? ff[r] : 0.0) / o.dt + o.gain * e[r] / o.dt;
    double* qdot = qdot_out + k * n_;
    solve_rows(q.data(), rhs, qdot);
    Eigen::Map<Vector>(q_out + k * n_, n_) = q;
    const Eigen::Map<const Vector> qd(qdot, n_);
    if (!qd.allFinite() || !(q + o.dt * qd).allFinite())
      throw std::invalid_argument("poses: the joint velocities are not finite at step " + std::to_string(k) +
                                  " (targets too far away for gain and dt)");
    q += o.dt * qd;
    if (o.saturate) q = q.cwiseMax(chain_.lower()).cwiseMin(chain_.upper());
  }
}

}  // namespace robokin
