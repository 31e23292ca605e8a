// Cuspidality of general 3R arms: the aspects on a grid of the (q2, q3) torus, the cusp points of the
// singular curves, and a posture change that meets no singularity.
#include "robokin/cuspidal.hpp"
#include "arm_3r.hpp"
#include "robokin/angles.hpp"
#include "robokin/general_3r.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace robokin {
namespace {

using namespace arm_3r_model;

// The image of the singular curve's tangent, D tau, at (t2, t3).
Eigen::Vector2d image_tangent(const Arm3R& a, double t2, double t3) {
  const double h = 1e-6;
  const double g2 = (det_t(a, t2 + h, t3) - det_t(a, t2 - h, t3)) / (2 * h);
  const double g3 = (det_t(a, t2, t3 + h) - det_t(a, t2, t3 - h)) / (2 * h);
  const Local L = local(a, t2, t3);
  const double rho = std::hypot(L.u.x(), L.u.y());
  Eigen::Matrix2d D;
  D << (L.u.x() * L.du2.x() + L.u.y() * L.du2.y()) / rho, (L.u.x() * L.du3.x() + L.u.y() * L.du3.y()) / rho,
      L.du2.z(), L.du3.z();
  return D * Eigen::Vector2d(-g3, g2);
}

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

// The torus grid of cuspidal: angle(i) = -pi + (i + 0.37) 2 pi / N, i taken modulo N.
struct TorusGrid {
  int N;
  double step, off;
  explicit TorusGrid(int n) : N(n), step(2 * kPi / n), off(0.37 * step) {}
  double angle(int i) const { return -kPi + off + step * ((i % N + N) % N); }
};

// sign(det J) (joint variables) into res.sign, and det J at the angles t = s q (smooth across
// axis 1) into the returned grid, row = q2.
std::vector<double> sample_det(const Arm3R& arm, const TorusGrid& G, Cuspidality& res) {
  const int N = G.N;
  res.sign = Cuspidality::Signs::Zero(N, N);
  std::vector<double> dd(static_cast<size_t>(N) * N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const double q2 = G.angle(i), q3 = G.angle(j);
      const double d = det_3r(arm, q2, q3);
      res.sign(i, j) = static_cast<std::int8_t>(sign_of(d));
      dd[i * N + j] = det_t(arm, arm.scale[1] * q2, arm.scale[2] * q3);
    }
  return dd;
}

// Whether the grid step from cell (i, j) by (di, dj) keeps det J of sign `sign` all along. Two cells
// of one sign may still be parted by two singular curves crossing between them (opposite quadrants
// of a crossing have the same sign): the step must keep it. Nor may det J touch 0 between them
// without changing sign (a double zero, as where the tool crosses axis 1 of an arm whose first two
// axes intersect): a dip of |det J| along the step is followed down to its minimum.
bool step_keeps_sign(const Arm3R& arm, const TorusGrid& G, int i, int j, int di, int dj, int sign) {
  const double step = G.step;
  const auto det_at_u = [&](double u) { return det_3r(arm, G.angle(i) + u * di * step, G.angle(j) + u * dj * step); };
  bool kept = true;
  double v[9];
  for (int m = 0; m <= 8 && kept; ++m) {
    v[m] = det_at_u(m / 8.0);
    kept = sign_of(v[m]) == sign;
  }
  for (int m = 1; m < 8 && kept; ++m) {
    if (!(std::abs(v[m]) <= std::abs(v[m - 1]) && std::abs(v[m]) <= std::abs(v[m + 1]) &&
          std::abs(v[m]) < 0.25 * std::min(std::abs(v[0]), std::abs(v[8]))))
      continue;
    double lo = (m - 1) / 8.0, hi = (m + 1) / 8.0;
    for (int it = 0; it < 60; ++it) {  // ternary search for the minimum of |det J|
      const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      if (std::abs(det_at_u(a)) < std::abs(det_at_u(b))) hi = b;
      else lo = a;
    }
    const double dmin = det_at_u(0.5 * (lo + hi));
    kept = sign_of(dmin) == sign &&
           std::abs(dmin) > 1e-6 * std::min(std::abs(v[0]), std::abs(v[8]));
  }
  return kept;
}

// The 4 neighbours of cell c = i N + j on the torus, by the steps (kStepI, kStepJ).
constexpr int kStepI[4] = {1, -1, 0, 0}, kStepJ[4] = {0, 0, 1, -1};
std::array<int, 4> neighbours(int N, int c) {
  const int i = c / N, j = c % N;
  return {((i + 1) % N) * N + j, ((i + N - 1) % N) * N + j, i * N + (j + 1) % N, i * N + (j + N - 1) % N};
}

// Aspects: the 4-connected components of one sign of det J on the torus (res.label, res.aspects),
// a step joining two cells only where det J keeps its sign along it.
void label_aspects(const Arm3R& arm, const TorusGrid& G, Cuspidality& res) {
  const int N = G.N;
  const std::int8_t* sign = res.sign.data();  // row-major: cell (i, j) at i N + j
  res.label = Cuspidality::Labels::Constant(N, N, -1);
  std::int32_t* label = res.label.data();
  for (int s = 0; s < N * N; ++s) {
    if (label[s] >= 0 || sign[s] == 0) continue;
    std::vector<int> stack = {s};
    label[s] = res.aspects;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const int i = c / N, j = c % N;
      const std::array<int, 4> nb = neighbours(N, c);
      for (int k = 0; k < 4; ++k) {
        const int n = nb[k];
        if (label[n] >= 0 || sign[n] != sign[s]) continue;
        if (step_keeps_sign(arm, G, i, j, kStepI[k], kStepJ[k], sign[s])) label[n] = res.aspects, stack.push_back(n);
      }
    }
    ++res.aspects;
  }
}

// det D (as det J at t = s q) and its gradient by central differences, at x = (t2, t3).
double det_at(const Arm3R& arm, const Eigen::Vector2d& x) { return det_t(arm, x(0), x(1)); }

Eigen::Vector2d det_gradient(const Arm3R& arm, const Eigen::Vector2d& x, double h) {
  return Eigen::Vector2d((det_at(arm, x + Eigen::Vector2d(h, 0)) - det_at(arm, x - Eigen::Vector2d(h, 0))) / (2 * h),
                         (det_at(arm, x + Eigen::Vector2d(0, h)) - det_at(arm, x - Eigen::Vector2d(0, h))) / (2 * h));
}

// Distance of the workspace point of (t2, t3) from axis 1.
double rho_at(const Arm3R& arm, const Eigen::Vector2d& x) {
  const Local L = local(arm, x(0), x(1));
  return std::hypot(L.u.x(), L.u.y());
}

// The zero of det D on the edge a -> b (fa = det D at a, the other end of opposite sign), by
// bisection; false where det D is NaN or the point is on (near) axis 1, where the map to
// (rho, z) is not smooth and no cusp of the workspace is sought.
bool edge_crossing(const Arm3R& arm, Eigen::Vector2d a, Eigen::Vector2d b, double fa, Eigen::Vector2d& x) {
  for (int it = 0; it < 60; ++it) {
    const Eigen::Vector2d m = 0.5 * (a + b);
    const double fm = det_at(arm, m);
    if (std::isnan(fm)) return false;
    if ((fm > 0) == (fa > 0)) a = m, fa = fm;
    else b = m;
  }
  x = 0.5 * (a + b);
  // On (near) axis 1 the map to (rho, z) is not smooth: no cusp of the workspace is sought there.
  return rho_at(arm, x) > 1e-3 * arm.size;
}

// The crossings of det D = 0 with the edges of grid cell (i, j) (corners unwrapped, t = s q, so
// the cell is a square even across +-pi); none when a corner's det is not finite.
std::vector<Eigen::Vector2d> cell_crossings(const Arm3R& arm, const TorusGrid& G, const std::vector<double>& dd, int i,
                                            int j) {
  const int N = G.N;
  const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
  double v[4];
  Eigen::Vector2d corner[4];
  bool finite = true;
  for (int k = 0; k < 4; ++k) {
    v[k] = dd[(ci[k] % N) * N + cj[k] % N];
    // Unwrapped corner coordinates (t = s q), so the cell is a square even across +-pi.
    corner[k] = Eigen::Vector2d(arm.scale[1] * (-kPi + G.off + G.step * ci[k]), arm.scale[2] * (-kPi + G.off + G.step * cj[k]));
    finite = finite && std::isfinite(v[k]);
  }
  std::vector<Eigen::Vector2d> xs;
  if (!finite) return xs;
  for (int k = 0; k < 4; ++k) {
    const int l = (k + 1) % 4;
    if ((v[k] > 0) != (v[l] > 0)) {
      Eigen::Vector2d x;
      if (edge_crossing(arm, corner[k], corner[l], v[k], x)) xs.push_back(x);
    }
  }
  return xs;
}

// Between two crossings whose image tangents D tau point opposite ways (ta the first's): the point
// where D tau reverses, by bisection along the curve (each midpoint pulled back onto det D = 0 by
// Newton along its gradient); false when the pull-back fails.
bool reversal_between(const Arm3R& arm, Eigen::Vector2d a, Eigen::Vector2d b, const Eigen::Vector2d& ta,
                      Eigen::Vector2d& x) {
  x = a;
  for (int it = 0; it < 50; ++it) {
    x = 0.5 * (a + b);
    for (int k = 0; k < 4; ++k) {  // Newton onto det D = 0 along its gradient
      const double h = 1e-7, fx = det_at(arm, x);
      const Eigen::Vector2d gr = det_gradient(arm, x, h);
      if (!(gr.squaredNorm() > 0) || !std::isfinite(fx)) return false;
      x -= fx * gr / gr.squaredNorm();
    }
    const Eigen::Vector2d tx = image_tangent(arm, x(0), x(1));
    if (tx.dot(ta) > 0) a = x;
    else b = x;
  }
  return true;
}

// The cusp in grid cell (i, j), if any, into res.cusps (each once): a cell crossed once by
// det D = 0 (two sign changes on its edges) whose image tangents at the two crossings point
// opposite ways has a cusp in between.
void cusp_in_cell(const Arm3R& arm, const TorusGrid& G, const std::vector<double>& dd, int i, int j,
                  Cuspidality& res) {
  const std::vector<Eigen::Vector2d> xs = cell_crossings(arm, G, dd, i, j);
  if (xs.size() != 2) return;
  Eigen::Vector2d ta = image_tangent(arm, xs[0](0), xs[0](1)), tb = image_tangent(arm, xs[1](0), xs[1](1));
  if (!(ta.dot(tb) < 0)) return;
  Eigen::Vector2d x;
  if (!reversal_between(arm, xs[0], xs[1], ta, x)) return;
  // Where two singular curves cross (det J factors, as for the arms of Pieper's conditions),
  // D tau also reverses, but there grad det D vanishes: not a cusp of a smooth curve.
  const auto grad_norm = [&](const Eigen::Vector2d& y) {
    const Eigen::Vector2d gr = det_gradient(arm, y, 1e-7);
    return std::hypot(gr(0), gr(1));
  };
  if (!(grad_norm(x) > 1e-2 * std::max(grad_norm(xs[0]), grad_norm(xs[1])))) return;
  // On axis 1 det D is not smooth (rho is not): no cusp point of the workspace there.
  if (rho_at(arm, x) < 1e-4 * arm.size) return;
  const double q2 = wrap_angle(x(0) * arm.scale[1]), q3 = wrap_angle(x(1) * arm.scale[2]);
  for (Eigen::Index k = 0; k < res.cusps.rows(); ++k)
    if (std::abs(wrap_angle(res.cusps(k, 0) - q2)) < 1e-5 && std::abs(wrap_angle(res.cusps(k, 1) - q3)) < 1e-5) return;
  const Local L = local(arm, x(0), x(1));
  res.cusps.conservativeResize(res.cusps.rows() + 1, Eigen::NoChange);
  res.cusps.row(res.cusps.rows() - 1) << q2, q3, std::hypot(L.u.x(), L.u.y()), L.u.z();
}

// The cell of the grid nearest (q2, q3), as i N + j.
int nearest_cell(const TorusGrid& G, double q2, double q3) {
  const auto index = [&](double q) {
    const long k = std::lround(std::remainder(q - G.angle(0), 2 * kPi) / G.step);
    return static_cast<int>(((k % G.N) + G.N) % G.N);
  };
  return index(q2) * G.N + index(q3);
}

// The shortest 4-connected path of cells from a to b within a's aspect (on the torus), a and b
// included; empty when there is none. prev: N x N cells of scratch, reused from call to call.
std::vector<int> cells_between(const Cuspidality& res, int N, int a, int b, std::vector<int>& prev) {
  const std::int32_t* label = res.label.data();
  prev.assign(static_cast<size_t>(N) * N, -2);  // -2: not reached; -1: the start
  std::deque<int> todo = {a};
  prev[a] = -1;
  while (!todo.empty()) {
    const int c = todo.front();
    todo.pop_front();
    if (c == b) {
      std::vector<int> cells;
      for (int x = c; x >= 0; x = prev[x]) cells.push_back(x);
      std::reverse(cells.begin(), cells.end());
      return cells;
    }
    for (const int n : neighbours(N, c))
      if (prev[n] == -2 && label[n] == label[a]) prev[n] = c, todo.push_back(n);
  }
  return {};
}

// The joints from qa through the cells' grid angles to qb, each step of q2 and q3 the short way
// round and q1 turned evenly the short way; empty unless det J keeps qa's sign all along (at 9
// points of each step).
Cuspidality::Path joint_path(const Arm3R& arm, const TorusGrid& G, const double* qa, const double* qb,
                             const std::vector<int>& cells) {
  const Eigen::Index m = static_cast<Eigen::Index>(cells.size()) + 2;
  Cuspidality::Path path(m, 3);
  path.row(0) << qa[0], qa[1], qa[2];
  for (size_t k = 0; k < cells.size(); ++k) path.row(k + 1) << 0.0, G.angle(cells[k] / G.N), G.angle(cells[k] % G.N);
  path.row(m - 1) << 0.0, qb[1], qb[2];
  const double dq1 = wrap_angle(qb[0] - qa[0]);
  for (Eigen::Index k = 1; k < m; ++k) {
    for (int c = 1; c < 3; ++c) path(k, c) = path(k - 1, c) + wrap_angle(path(k, c) - path(k - 1, c));
    path(k, 0) = qa[0] + dq1 * static_cast<double>(k) / static_cast<double>(m - 1);
  }
  const int s0 = sign_of(det_3r(arm, qa[1], qa[2]));
  for (Eigen::Index k = 0; k + 1 < m; ++k)
    for (int u = 0; u <= 8; ++u) {
      const Eigen::RowVector3d q = path.row(k) + (u / 8.0) * (path.row(k + 1) - path.row(k));
      if (sign_of(det_3r(arm, q(1), q(2))) != s0) return {};
    }
  return path;
}

// Two of the solutions s of p in one aspect (their cells' label, and det J of their cells' sign)
// joined by a joint path that keeps det J's sign: into res.point and res.path.
bool two_in_one_aspect(const Arm3R& arm, const TorusGrid& G, const ClosedFormSolutions& s, const Eigen::Vector3d& p,
                       std::vector<int>& scratch, Cuspidality& res) {
  const int N = G.N;
  for (int x = 0; x < s.count(); ++x)
    for (int y = x + 1; y < s.count(); ++y) {
      const double *qa = s.row(x), *qb = s.row(y);
      const int a = nearest_cell(G, qa[1], qa[2]), b = nearest_cell(G, qb[1], qb[2]);
      const int la = res.label.data()[a];
      if (la < 0 || la != res.label.data()[b]) continue;
      if (sign_of(det_3r(arm, qa[1], qa[2])) != res.sign.data()[a] ||
          sign_of(det_3r(arm, qb[1], qb[2])) != res.sign.data()[b])
        continue;
      const std::vector<int> cells = cells_between(res, N, a, b, scratch);
      if (cells.empty()) continue;
      Cuspidality::Path path = joint_path(arm, G, qa, qb, cells);
      if (path.rows() == 0) continue;
      res.point = p;
      res.path = std::move(path);
      return true;
    }
  return false;
}

// Direction i of kDirections spread evenly over the unit sphere (a Fibonacci lattice: heights
// evenly spaced, longitudes turning by the golden angle), turned about z by `turn`.
constexpr int kRadii = 5, kDirections = 24;
Eigen::Vector3d direction(int i, double turn) {
  const double z = 1 - (2 * i + 1) / static_cast<double>(kDirections), r = std::sqrt(1 - z * z);
  const double longitude = i * kPi * (3 - std::sqrt(5.0)) + turn;
  return {r * std::cos(longitude), r * std::sin(longitude), z};
}

// The posture change of a cuspidal arm: tool points around each cusp (where three solutions
// coincide, two stay close and in one aspect), at 1e-3 to 1e-1 x the arm's size, 24 directions at
// each (the lattice turned by a fifth of a turn from one distance to the next), until
// two_in_one_aspect finds one. res.point and res.path stay
// empty otherwise.
void posture_change(const Arm3R& arm, const Chain& chain, const TorusGrid& G, Cuspidality& res) {
  const double radii[kRadii] = {1e-3, 3e-3, 1e-2, 3e-2, 1e-1};
  const JointLimits none;
  std::vector<int> scratch;
  for (Eigen::Index k = 0; k < res.cusps.rows(); ++k) {
    const double t[3] = {0.0, arm.scale[1] * res.cusps(k, 0), arm.scale[2] * res.cusps(k, 1)};
    const Eigen::Vector3d cusp = position(arm, t);
    for (int r = 0; r < kRadii; ++r)
      for (int i = 0; i < kDirections; ++i) {
        const Eigen::Vector3d p = cusp + radii[r] * arm.size * direction(i, 2 * kPi * r / kRadii);
        if (two_in_one_aspect(arm, G, ik_general_3r(arm, chain, p, none), p, scratch, res)) return;
      }
  }
}

}  // namespace

void CuspidalOptions::validate() const {
  if (resolution < 16 || resolution > 4096)
    throw std::invalid_argument("resolution: expected an int in [16, 4096] (grid points per joint), got " +
                                std::to_string(resolution));
}

Cuspidality cuspidal(const Chain& chain, const CuspidalOptions& options) {
  options.validate();
  const int resolution = options.resolution;
  const Arm3R arm = arm_3r(chain);
  const TorusGrid G(resolution);
  Cuspidality res;
  res.grid.resize(resolution);
  for (int i = 0; i < resolution; ++i) res.grid(i) = G.angle(i);
  const std::vector<double> dd = sample_det(arm, G, res);
  label_aspects(arm, G, res);
  for (int i = 0; i < resolution; ++i)
    for (int j = 0; j < resolution; ++j) cusp_in_cell(arm, G, dd, i, j, res);
  res.cuspidal = res.cusps.rows() > 0;
  if (res.cuspidal) posture_change(arm, chain, G, res);
  return res;
}

}  // namespace robokin
