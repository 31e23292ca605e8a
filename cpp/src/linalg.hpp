// Linear algebra written once for the core: the L D L^T factorisation of a small symmetric matrix
// (the damped steps below, the numerical IK's normal equations, Yoshikawa's measure in
// manipulability.cpp); the damped least-squares (minimum-norm) step with its singular fallback,
// shared by the Reach loop (reach.cpp), resolved-rate control (resolved_rate.cpp) and the numerical
// IK's Newton steps (ik_numeric.cpp); the RPR study's homogeneous term; the overflow-safe norm of an error.
#pragma once

#include <Eigen/Dense>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

namespace robokin {

// A = L D L^T in place for a symmetric A (L unit lower triangular, D diagonal): L's strict lower part
// in A's, 1 / D on A's diagonal (one division a column, no square root: the factorisation is a
// chain of dependent columns, and these are its longest latencies); the upper half is not read.
// Written out for A's size (fixed: unrolled, no calls; dynamic up to 6 rows: no allocation). False
// when a pivot is not positive (A not positive definite); dmin and dmax are the smallest and largest
// pivots (D's entries, the squares of a Cholesky factor's diagonal).
template <class Mat>
bool ldlt_in_place(Mat& A, double& dmin, double& dmax) {
  constexpr int kMax = Mat::MaxRowsAtCompileTime;
  static_assert(kMax != Eigen::Dynamic, "ldlt_in_place: a matrix of bounded size");
  const int n = static_cast<int>(A.rows());
  double d[kMax], v[kMax];
  dmin = std::numeric_limits<double>::infinity();
  dmax = 0.0;
  for (int j = 0; j < n; ++j) {
    double dj = A(j, j);
    for (int k = 0; k < j; ++k) {
      v[k] = A(j, k) * d[k];  // L(j, k) D(k)
      dj -= A(j, k) * v[k];
    }
    if (!(dj > 0.0)) return false;  // also NaN
    d[j] = dj;
    dmin = std::min(dmin, dj);
    dmax = std::max(dmax, dj);
    const double inv = 1.0 / dj;
    A(j, j) = inv;
    for (int i = j + 1; i < n; ++i) {
      double x = A(i, j);
      for (int k = 0; k < j; ++k) x -= A(i, k) * v[k];
      A(i, j) = x * inv;
    }
  }
  return true;
}

// y <- (L D L^T)^-1 y for ldlt_in_place's factors: two unit triangular solves and the diagonal.
template <class Mat, class Vec>
void ldlt_solve_in_place(const Mat& L, Vec& y) {
  const int n = static_cast<int>(L.rows());
  for (int i = 0; i < n; ++i)  // L z = y
    for (int k = 0; k < i; ++k) y(i) -= L(i, k) * y(k);
  for (int i = n - 1; i >= 0; --i) {  // D L^T x = z
    y(i) *= L(i, i);
    for (int k = i + 1; k < n; ++k) y(i) -= L(k, i) * y(k);
  }
}

// out <- J^T (J J^T + lambda^2 I)^-1 rhs, the minimum-norm (damped) solution of J out = rhs; the
// least-squares minimum-norm solution when J J^T is singular and lambda = 0. M task rows: the
// M x M system is solved by ldlt_in_place (no pivoting: J J^T is symmetric positive semi-definite),
// and handed to a complete orthogonal decomposition of J when it is (nearly) singular: a Cholesky
// factor's smallest diagonal entry below 1e-9 times its largest (the pivots' square roots).
template <int M, class JMap, class Out>
void min_norm_solve(const JMap& J, const Eigen::Matrix<double, M, 1>& rhs, double damping, Out& out) {
  Eigen::Matrix<double, M, M> A;
  A.noalias() = J * J.transpose();
  A.diagonal().array() += damping * damping;
  double dmin, dmax;
  if (ldlt_in_place(A, dmin, dmax) && std::sqrt(dmin) > 1e-9 * std::max(1.0, std::sqrt(dmax))) {
    Eigen::Matrix<double, M, 1> y = rhs;
    ldlt_solve_in_place(A, y);
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

// dq += (1 - J^p J) h with h = gains .* (qbar - q): the RPR study's homogeneous term (eqs. 5-7), which
// moves the joints toward the middle of their ranges without moving the tool (to first order); h is
// -grad of 1/2 sum gains_i (qbar_i - q_i)^2 (joint_limit_gains, reach.hpp: the seed's z).
// h and correction are workspace of the joints' size.
template <int M, class JMap, class G, class Q, class V>
void add_nullspace_term(const JMap& J, double damping, const G& gains, const G& qbar, const Q& q, V& h,
                        V& correction, V& dq) {
  h = gains.cwiseProduct(qbar - q);
  const Eigen::Matrix<double, M, 1> Jh = J * h;
  min_norm_solve<M>(J, Jh, damping, correction);
  dq += h - correction;
}

}  // namespace robokin
