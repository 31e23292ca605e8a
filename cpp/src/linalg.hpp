// Linear algebra written once for the core: the damped least-squares (minimum-norm) step with its
// singular fallback, shared by the Reach loop (reach.cpp), resolved-rate control
// (resolved_rate.cpp) and the numerical IK's Newton steps (ik_numeric.cpp); seed 000's homogeneous
// term; the overflow-safe norm of an error.
#pragma once

#include <Eigen/Dense>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

namespace robokin {

// out <- J^T (J J^T + lambda^2 I)^-1 rhs, the minimum-norm (damped) solution of J out = rhs; the
// least-squares minimum-norm solution when J J^T is singular and lambda = 0. M task rows: the
// M x M system is solved by a Cholesky factorisation written out for fixed M (no calls, no
// pivoting: J J^T is symmetric positive semi-definite), and handed to a complete orthogonal
// decomposition of J when it is (nearly) singular, as before.
template <int M, class JMap, class Out>
void min_norm_solve(const JMap& J, const Eigen::Matrix<double, M, 1>& rhs, double damping, Out& out) {
  Eigen::Matrix<double, M, M> A;
  A.noalias() = J * J.transpose();
  A.diagonal().array() += damping * damping;
  // A = L L^T, L lower triangular (stored in the lower half of A).
  bool ok = true;
  double dmin = std::numeric_limits<double>::infinity(), dmax = 0.0;
  for (int j = 0; j < M && ok; ++j) {
    double d = A(j, j);
    for (int k = 0; k < j; ++k) d -= A(j, k) * A(j, k);
    if (!(d > 0.0)) {
      ok = false;
      break;
    }
    d = std::sqrt(d);
    A(j, j) = d;
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
    for (int i = j + 1; i < M; ++i) {
      double x = A(i, j);
      for (int k = 0; k < j; ++k) x -= A(i, k) * A(j, k);
      A(i, j) = x / d;
    }
  }
  if (ok && dmin > 1e-9 * std::max(1.0, dmax)) {
    Eigen::Matrix<double, M, 1> y = rhs;
    for (int i = 0; i < M; ++i) {  // L z = rhs
      for (int k = 0; k < i; ++k) y(i) -= A(i, k) * y(k);
      y(i) /= A(i, i);
    }
    for (int i = M - 1; i >= 0; --i) {  // L^T y = z
      for (int k = i + 1; k < M; ++k) y(i) -= A(k, i) * y(k);
      y(i) /= A(i, i);
    }
    out.noalias() = J.transpose() * y;
  } else {
    out = Eigen::MatrixXd(J).completeOrthogonalDecomposition().solve(Eigen::VectorXd(rhs));
  }
}

// |v|, also when its squares overflow (a target beyond ~1e154): the scaled norm, only then.
template <class V>
double safe_norm(const V& v) {
  const double n = v.norm();
  return std::isfinite(n) ? n : v.stableNorm();
}

// dq += (1 - J^p J) h with h = weights .* (qbar - q): seed 000's homogeneous term (eqs. 5-7), which
// moves the joints toward the middle of their ranges without moving the tool (to first order).
// h and correction are workspace of the joints' size.
template <int M, class JMap, class W, class Q, class V>
void add_nullspace_term(const JMap& J, double damping, const W& weights, const W& qbar, const Q& q, V& h,
                        V& correction, V& dq) {
  h = weights.cwiseProduct(qbar - q);
  const Eigen::Matrix<double, M, 1> Jh = J * h;
  min_norm_solve<M>(J, Jh, damping, correction);
  dq += h - correction;
}

}  // namespace robokin
