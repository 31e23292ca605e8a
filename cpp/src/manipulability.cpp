#include "robokin/manipulability.hpp"
#include "robokin/parallel.hpp"

#include "linalg.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace robokin {

Measure parse_measure(const std::string& name) {
  if (name == "yoshikawa") return Measure::Yoshikawa;
  if (name == "condition") return Measure::Condition;
  if (name == "min_singular") return Measure::MinSingular;
  throw std::invalid_argument("measure: expected one of 'yoshikawa', 'condition', 'min_singular', got '" + name + "'");
}

namespace {

// The Jacobian's task rows, up to 6 x 8 on the stack (most arms), larger on the heap.
using SmallJ = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 6, 8>;

template <class M>
double svd_measure(const M& J, Measure measure) {
  // Singular values only (no U, V); JacobiSVD works on the wider side's transpose as well.
  const Eigen::JacobiSVD<M> svd(J);
  const auto& s = svd.singularValues();  // decreasing, min(rows, cols) of them
  switch (measure) {
    case Measure::Yoshikawa: return s.prod();
    case Measure::MinSingular: return s(s.size() - 1);
    case Measure::Condition: return s(0) > 0 ? s(s.size() - 1) / s(0) : 0.0;
  }
  return 0.0;
}

// Yoshikawa's measure without the SVD: the product of the k = min(rows, cols) singular values is
// sqrt(det G), G = J J^T (or J^T J, k x k), i.e. the product of the diagonal of G's Cholesky factor
// L (a few hundred flops against the SVD's thousands). Its relative error is of the order of
// k eps cond(G), so it is used only when tr(G) |L^-1|_F^2 (an upper bound of cond(G)) is at most
// 1e5: on 1e5 random configurations of the UR5, the PUMA 560 and a 7R arm (90-100 % of them take
// this path) it agrees with numpy's SVD to 4e-12 relative at worst. Otherwise (near a
// singularity, or k > 6) the SVD.
template <class M>
bool yoshikawa_by_cholesky(const M& J, double& value) {
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 6, 6>;
  const long k = std::min(J.rows(), J.cols());
  if (k > 6) return false;
  // G's diagonal and lower triangle, all that ldlt_in_place reads: dot products of J's rows (or
  // columns), summed in order: Eigen's product of these runtime-sized matrices cost more than the
  // Jacobian itself. (A fixed-size 6 x 6 G, its loops unrolled, measured slower.)
  Small G(k, k);
  const bool by_rows = J.rows() <= J.cols();  // G = J J^T: J's rows, else J^T J: its columns
  const long len = by_rows ? J.cols() : J.rows();
  const long step = by_rows ? J.rows() : 1, next = by_rows ? 1 : J.rows();  // along a vector, between two
  const double* data = J.data();
  double trace = 0.0;
  for (long i = 0; i < k; ++i)
    for (long j = 0; j <= i; ++j) {
      const double *a = data + i * next, *b = data + j * next;
      double dot = 0.0;
      for (long t = 0; t < len; ++t) dot += a[t * step] * b[t * step];
      G(i, j) = dot;
      if (i == j) trace += dot;
    }
  // G = L_u D L_u^T (ldlt_in_place: L_u unit lower triangular, 1 / D on G's diagonal); the Cholesky
  // factor is L = L_u D^(1/2): its diagonal's product is prod sqrt(D_j), and L^-1 = D^(-1/2) L_u^-1.
  double dmin, dmax;
  if (!ldlt_in_place(G, dmin, dmax)) return false;
  double product = 1.0;
  for (long j = 0; j < k; ++j) product /= std::sqrt(G(j, j));
  // |L^-1|_F^2 = sum_r (1 / D_r) sum_c (L_u^-1)_rc^2, column by column of L_u^-1 (forward
  // substitution on the identity).
  double inverse_norm2 = 0.0;
  double x[6];
  for (long c = 0; c < k; ++c) {
    x[c] = 1.0;
    inverse_norm2 += G(c, c);
    for (long r = c + 1; r < k; ++r) {
      double v = 0.0;
      for (long i = c; i < r; ++i) v -= G(r, i) * x[i];
      x[r] = v;
      inverse_norm2 += G(r, r) * v * v;
    }
  }
  if (!(std::isfinite(product) && trace * inverse_norm2 <= 1e5)) return false;
  value = product;
  return true;
}

template <class M>
double measure_of(const M& J, Measure measure) {
  double value;
  if (measure == Measure::Yoshikawa && yoshikawa_by_cholesky(J, value)) return value;
  return svd_measure(J, measure);
}

class Evaluator {
 public:
  Evaluator(const Chain& chain, Task task)
      : chain_(chain), task_(task), heap_(chain.dof() > 16 ? 6 * chain.dof() : 0) {}
  double operator()(const double* q, Measure measure) {
    const int n = chain_.dof(), m = task_rows(task_);
    const int* rows = task_row_indices(task_);
    double* buffer = n > 16 ? heap_.data() : stack_;
    Rigid T;
    chain_.fk_jacobian(q, T, buffer);
    const Eigen::Map<const Matrix6X> J6(buffer, 6, n);
    if (n <= 8) {
      SmallJ J(m, n);
      for (int r = 0; r < m; ++r) J.row(r) = J6.row(rows[r]);
      return measure_of(J, measure);
    }
    Eigen::MatrixXd J(m, n);
    for (int r = 0; r < m; ++r) J.row(r) = J6.row(rows[r]);
    return measure_of(J, measure);
  }

 private:
  const Chain& chain_;
  Task task_;
  double stack_[6 * 16];  // the 6 x n Jacobian of up to 16 joints
  std::vector<double> heap_;
};

}  // namespace

double manipulability(const Chain& chain, const double* q, Task task, Measure measure) {
  return Evaluator(chain, task)(q, measure);
}

void manipulability_batch(const Chain& chain, const double* q, long count, Task task, Measure measure, double* out,
                          Progress* progress) {
  const long n = chain.dof();
  parallel_for(
      count, 256,
      [&](long begin, long end) {
        Evaluator eval(chain, task);
        for (long k = begin; k < end; ++k) out[k] = eval(q + k * n, measure);
      },
      progress);
}

void ellipsoid(const Chain& chain, const double* q, bool rotation, Eigen::Matrix3d& axes, Eigen::Vector3d& lengths) {
  const int n = chain.dof();
  Matrix6X J6(6, n);
  Rigid T;
  chain.fk_jacobian(q, T, J6.data());
  const Eigen::MatrixXd J = J6.middleRows(rotation ? 3 : 0, 3);
  // Full U: with fewer than 3 joints the missing axes have length 0.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU);
  axes = svd.matrixU();
  lengths.setZero();
  const auto& s = svd.singularValues();
  for (int i = 0; i < s.size(); ++i) lengths(i) = s(i);
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);  // a right-handed frame of axes
}

}  // namespace robokin
