// 3-RRR workspace maps (see rrr3_workspace.hpp).
#include "robokin/rrr3_workspace.hpp"

#include "robokin/parallel.hpp"

#include "rrr3_pose_eval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

std::uint8_t code(WorkspaceCell c) { return static_cast<std::uint8_t>(c); }

// A reachable cell's kind from the seed's classification (RRR3::singularity's).
WorkspaceCell cell_of(SingularKind kind) {
  return kind == SingularKind::Serial ? WorkspaceCell::Serial : kind == SingularKind::Parallel ? WorkspaceCell::Parallel : WorkspaceCell::Regular;
}

// The map's square of n x n cells about the poses every leg reaches at orientation phi (the
// intersection of the three discs |O_i - R(phi) b_i - E| <= l1 + l2), with a rim of unreachable
// cells; false, w.h left 0, when the discs do not meet.
bool place_grid(const RRR3& robot, double phi, long n, RRR3Workspace& w) {
  const double reach = robot.l1() + robot.l2();
  double xl = -1e300, xh = 1e300, yl = -1e300, yh = 1e300;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d c = robot.base_joint(i) - robot.platform_joint(Pose(0, 0, phi), i);  // O_i - R(phi) b_i
    xl = std::max(xl, c.x() - reach), xh = std::min(xh, c.x() + reach);
    yl = std::max(yl, c.y() - reach), yh = std::min(yh, c.y() + reach);
  }
  if (n <= 0 || xl >= xh || yl >= yh) return false;
  const double half = 0.5 * std::max(xh - xl, yh - yl) * 1.02;  // a rim of unreachable cells
  w.h = 2 * half / n;
  w.x0 = 0.5 * (xl + xh) - half;
  w.y0 = 0.5 * (yl + yh) - half;
  return true;
}

// Every cell's kind from the shared pose evaluation (rrr3_pose_eval.hpp: the determinants only, the
// map does not need the distance), and det A / R_e per cell (0 where unreachable).
std::vector<double> classify_cells(const RRR3& robot, const RRR3WorkspaceOptions& options, RRR3Workspace& w,
                                   Progress* progress) {
  // Locals, not the structs' fields: the cells are bytes, whose stores may alias any field.
  const long n = options.n;
  const double phi = options.phi, tol = options.tol, x0 = w.x0, y0 = w.y0, h = w.h;
  const Mode mode = options.mode;
  std::uint8_t* cells = w.cells.data();
  std::vector<double> det_a(n * n, 0.0);
  parallel_for(n, 16, [&](long j0, long j1) {
    // One row's inverse model at once (RRR3::ik_batch: RRR3::ik's bits, NaN rows where a leg
    // cannot reach; a row is below its threshold for threads, so it runs here).
    std::vector<double> poses(3 * n), alpha(3 * n);
    for (long j = j0; j < j1; ++j) {
      const double y = y0 + (j + 0.5) * h;
      for (long i = 0; i < n; ++i) poses[3 * i] = x0 + (i + 0.5) * h, poses[3 * i + 1] = y, poses[3 * i + 2] = phi;
      robot.ik_batch(poses.data(), n, mode, alpha.data());
      for (long i = 0; i < n; ++i) {
        const Eigen::Vector3d a(alpha[3 * i], alpha[3 * i + 1], alpha[3 * i + 2]);
        if (std::isnan(a(0))) continue;  // unreachable
        Eigen::Matrix3d A, B;
        const PoseMeasures m = measures_at(robot, Pose(poses[3 * i], y, phi), a, A, B);
        if (!m.finite) continue;  // unreachable, as for evaluate_pose
        const double da = m.det_a_norm, db = m.det_b_norm;
        det_a[j * n + i] = da;
        cells[j * n + i] = code(cell_of(singular_kind(da, db, tol)));
      }
    }
  }, progress);
  return det_a;
}

// A sign change of det A between two reachable neighbours: the cell of smaller |det A| marked
// parallel (a regular cell only; the singularity is crossed between the cells' centres).
void mark_sign_changes(RRR3Workspace& w, const std::vector<double>& det_a) {
  const long n = w.n;
  auto reachable = [&](long c) { return w.cells[c] != code(WorkspaceCell::Unreachable); };
  std::vector<long> crossing;
  for (long j = 0; j < n; ++j)
    for (long i = 0; i < n; ++i) {
      const long c = j * n + i;
      if (!reachable(c)) continue;
      for (long nb : {i + 1 < n ? c + 1 : -1L, j + 1 < n ? c + n : -1L}) {
        if (nb < 0 || !reachable(nb) || (det_a[c] < 0) == (det_a[nb] < 0)) continue;
        crossing.push_back(std::abs(det_a[c]) <= std::abs(det_a[nb]) ? c : nb);
      }
    }
  for (long c : crossing)
    if (w.cells[c] == code(WorkspaceCell::Regular)) w.cells[c] = code(WorkspaceCell::Parallel);
}

// The cells of the 4-connected region of regular cells containing c, marked seen (flood fill).
long region_size(const RRR3Workspace& w, long c, std::vector<char>& seen, std::vector<long>& stack) {
  const long n = w.n;
  long size = 0;
  stack.assign(1, c);
  seen[c] = 1;
  while (!stack.empty()) {
    const long k = stack.back();
    stack.pop_back();
    ++size;
    const long i = k % n, j = k / n;
    for (long nb : {i > 0 ? k - 1 : -1L, i + 1 < n ? k + 1 : -1L, j > 0 ? k - n : -1L, j + 1 < n ? k + n : -1L})
      if (nb >= 0 && !seen[nb] && w.cells[nb] == code(WorkspaceCell::Regular)) {
        seen[nb] = 1;
        stack.push_back(nb);
      }
  }
  return size;
}

// The areas: reachable cells, regular cells, the largest singularity-free region.
void measure_areas(RRR3Workspace& w, Progress* progress) {
  const long n = w.n;
  const double cell = w.h * w.h;
  long reachable_count = 0, regular_count = 0, best = 0;
  std::vector<char> seen(n * n, 0);
  std::vector<long> stack;
  for (long c = 0; c < n * n; ++c) {
    if (c % n == 0) report(progress, n, n);  // the map is done; Ctrl-C is still heard while labelling
    reachable_count += w.cells[c] != code(WorkspaceCell::Unreachable);
    if (w.cells[c] != code(WorkspaceCell::Regular)) continue;
    ++regular_count;
    if (seen[c]) continue;
    best = std::max(best, region_size(w, c, seen, stack));
  }
  w.reachable_area = reachable_count * cell;
  w.regular_area = regular_count * cell;
  w.region_area = best * cell;
}

}  // namespace

void RRR3WorkspaceOptions::validate() const {
  if (!std::isfinite(phi)) throw std::invalid_argument("phi: must be finite");
  check_mode(mode);
  if (n < 2 || n > 5000) throw std::invalid_argument("n: expected a grid size in [2, 5000], got " + std::to_string(n));
  if (!(std::isfinite(tol) && tol > 0)) throw std::invalid_argument("tol: must be a positive finite number");
}

Eigen::VectorXd RRR3Workspace::x() const {
  return (x0 + (Eigen::VectorXd::LinSpaced(n, 0, static_cast<double>(n - 1)).array() + 0.5) * h).matrix();
}

Eigen::VectorXd RRR3Workspace::y() const {
  return (y0 + (Eigen::VectorXd::LinSpaced(n, 0, static_cast<double>(n - 1)).array() + 0.5) * h).matrix();
}

std::array<double, 4> RRR3Workspace::extent() const {
  return {x0, x0 + static_cast<double>(n) * h, y0, y0 + static_cast<double>(n) * h};
}

RRR3Workspace workspace(const RRR3& robot, const RRR3WorkspaceOptions& options, Progress* progress) {
  options.validate();
  RRR3Workspace w;
  w.n = options.n;
  w.cells.assign(w.n * w.n, 0);
  if (!place_grid(robot, options.phi, w.n, w)) return w;
  const std::vector<double> det_a = classify_cells(robot, options, w, progress);
  mark_sign_changes(w, det_a);
  measure_areas(w, progress);
  return w;
}

std::vector<double> region_areas(const std::vector<RRR3>& robots, const RRR3WorkspaceOptions& options,
                                 Progress* progress) {
  options.validate();
  std::vector<double> out;
  out.reserve(robots.size());
  const long parts = static_cast<long>(robots.size());
  for (long k = 0; k < parts; ++k) {
    PartProgress part(progress, k, parts);
    out.push_back(workspace(robots[k], options, progress ? &part : nullptr).region_area);
  }
  return out;
}

}  // namespace robokin
