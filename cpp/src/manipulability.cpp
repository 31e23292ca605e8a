#include "robokin/manipulability.hpp"
#include "robokin/parallel.hpp"

#include <Eigen/SVD>

#include <algorithm>
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
double measure_of(const M& J, Measure measure) {
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

class Evaluator {
 public:
  Evaluator(const Chain& chain, Task task) : chain_(chain), task_(task), J6_(6 * chain.dof()) {}
  double operator()(const double* q, Measure measure) {
    const int n = chain_.dof(), m = task_rows(task_);
    const int* rows = task_row_indices(task_);
    Rigid T;
    chain_.fk_jacobian(q, T, J6_.data());
    const Eigen::Map<const Matrix6X> J6(J6_.data(), 6, n);
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
  std::vector<double> J6_;
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
