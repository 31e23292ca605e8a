// 3-RRR workspace maps (see rrr3_workspace.hpp).
#include "robokin/rrr3_workspace.hpp"

#include "robokin/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

// det A / R_e and det B / l1^3 at one pose whose actuated angles alpha (RRR3::ik's) are known: the
// robot's own Jacobians (RRR3::jacobians_at), one implementation for the map, RRR3::singularity
// and the planner.
void dets(const RRR3& robot, const Pose& pose, const Eigen::Vector3d& alpha, double& det_a, double& det_b) {
  Eigen::Matrix3d A, B;
  robot.jacobians_at(pose, robot.elbows(alpha), A, B);
  det_a = A.determinant() / robot.platform_radius();
  det_b = B.determinant() / (robot.l1() * robot.l1() * robot.l1());
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
  const double phi = options.phi, tol = options.tol;
  const Mode& mode = options.mode;
  const long n = options.n;
  RRR3Workspace w;
  w.n = n;
  const double reach = robot.l1() + robot.l2();
  double xl = -1e300, xh = 1e300, yl = -1e300, yh = 1e300;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d c = robot.base_joint(i) - robot.platform_joint(Pose(0, 0, phi), i);  // O_i - R(phi) b_i
    xl = std::max(xl, c.x() - reach), xh = std::min(xh, c.x() + reach);
    yl = std::max(yl, c.y() - reach), yh = std::min(yh, c.y() + reach);
  }
  w.cells.assign(n * n, 0);
  if (n <= 0 || xl >= xh || yl >= yh) return w;
  const double half = 0.5 * std::max(xh - xl, yh - yl) * 1.02;  // a rim of unreachable cells
  w.h = 2 * half / n;
  w.x0 = 0.5 * (xl + xh) - half;
  w.y0 = 0.5 * (yl + yh) - half;

  std::vector<double> det_a(n * n, 0.0);
  parallel_for(n, 16, [&](long j0, long j1) {
    // One row's inverse model at once (RRR3::ik_batch: RRR3::ik's bits, NaN rows where a leg
    // cannot reach; a row is below its threshold for threads, so it runs here).
    std::vector<double> poses(3 * n), alpha(3 * n);
    for (long j = j0; j < j1; ++j) {
      const double y = w.y0 + (j + 0.5) * w.h;
      for (long i = 0; i < n; ++i) poses[3 * i] = w.x0 + (i + 0.5) * w.h, poses[3 * i + 1] = y, poses[3 * i + 2] = phi;
      robot.ik_batch(poses.data(), n, mode, alpha.data());
      for (long i = 0; i < n; ++i) {
        const Eigen::Vector3d a(alpha[3 * i], alpha[3 * i + 1], alpha[3 * i + 2]);
        if (std::isnan(a(0))) continue;  // unreachable
        double da, db;
        dets(robot, Pose(poses[3 * i], y, phi), a, da, db);
        det_a[j * n + i] = da;
        w.cells[j * n + i] = static_cast<std::uint8_t>(
            std::abs(db) < tol ? WorkspaceCell::Serial : std::abs(da) < tol ? WorkspaceCell::Parallel : WorkspaceCell::Regular);
      }
    }
  }, progress);
  // A sign change of det A between two reachable neighbours: mark the cell of smaller |det A|.
  auto reachable = [&](long c) { return w.cells[c] != static_cast<std::uint8_t>(WorkspaceCell::Unreachable); };
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
    if (w.cells[c] == static_cast<std::uint8_t>(WorkspaceCell::Regular)) w.cells[c] = static_cast<std::uint8_t>(WorkspaceCell::Parallel);

  const double cell = w.h * w.h;
  long reachable_count = 0, regular_count = 0, best = 0;
  std::vector<char> seen(n * n, 0);
  std::vector<long> stack;
  for (long c = 0; c < n * n; ++c) {
    if (c % n == 0) report(progress, n, n);  // the map is done; Ctrl-C is still heard while labelling
    reachable_count += reachable(c);
    if (w.cells[c] != static_cast<std::uint8_t>(WorkspaceCell::Regular)) continue;
    ++regular_count;
    if (seen[c]) continue;
    long size = 0;
    stack.assign(1, c);
    seen[c] = 1;
    while (!stack.empty()) {  // flood fill of one singularity-free region
      const long k = stack.back();
      stack.pop_back();
      ++size;
      const long i = k % n, j = k / n;
      for (long nb : {i > 0 ? k - 1 : -1L, i + 1 < n ? k + 1 : -1L, j > 0 ? k - n : -1L, j + 1 < n ? k + n : -1L})
        if (nb >= 0 && !seen[nb] && w.cells[nb] == static_cast<std::uint8_t>(WorkspaceCell::Regular)) {
          seen[nb] = 1;
          stack.push_back(nb);
        }
    }
    best = std::max(best, size);
  }
  w.reachable_area = reachable_count * cell;
  w.regular_area = regular_count * cell;
  w.region_area = best * cell;
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
