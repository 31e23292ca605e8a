// 3-RRR path planning with parallel-singularity avoidance: dynamic programming over a grid of
// orientations (see rrr3_plan.hpp).
#include "robokin/rrr3_plan.hpp"

#include "robokin/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>
#include <stdexcept>

namespace robokin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kForbidden = 1e12;  // cost of an unreachable, serial or wrong-sign orientation
constexpr double kShortfall = 1e8;   // weight of (margin - distance)^2 below the margin: nearly a constraint
constexpr double kMaxHalf = 1e5;     // orientations on each side of the nominal one
constexpr double kMaxBytes = 1024.0 * 1024 * 1024;  // memory of the grid (cells and back pointers)
constexpr double kMaxWork = 1e9;     // count * m * (2 w + 1) transitions of the dynamic programme

struct Cell {
  bool reachable = false;
  double det_a = kNaN, det_b = kNaN, distance = kNaN;
  Eigen::Vector3d alpha = Eigen::Vector3d::Constant(kNaN);
};

Cell evaluate(const RRR3& robot, const Pose& pose, const Mode& mode) {
  Cell c;
  if (robot.ik(pose, mode, c.alpha.data()) >= 0) {
    c.alpha.setConstant(kNaN);
    return c;
  }
  Eigen::Matrix3d A, B;
  robot.jacobians_at(pose, robot.elbows(c.alpha), A, B);
  c.reachable = true;
  c.det_a = A.determinant() / robot.platform_radius();
  c.det_b = B.determinant() / std::pow(robot.l1(), 3);
  c.distance = robot.distance(A);
  return c;
}

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

}  // namespace

void RRR3PlanOptions::validate() const {
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  check(std::isfinite(phi), "phi: must be finite");
  check(max_step > 0 && std::isfinite(max_step), "max_step: must be positive and finite");
  check(resolution > 0 && std::isfinite(resolution) && resolution <= max_step,
        "resolution: must be positive and at most max_step");
  check(span >= 0 && span <= M_PI, "span: must be in [0, pi]");
  check(margin >= 0 && std::isfinite(margin), "margin: must be >= 0 and finite");
  check(serial_margin >= 0 && std::isfinite(serial_margin), "serial_margin: must be >= 0 and finite");
  check(smoothing >= 0 && std::isfinite(smoothing), "smoothing: must be >= 0 and finite");
  check_mode(mode);
}

RRR3Plan plan_path(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& o,
                   Progress* progress) {
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  check(count >= 0, "points: negative count");
  o.validate();
  RRR3Plan plan;
  plan.poses.resize(count, 3);
  for (long k = 0; k < count; ++k) plan.poses.row(k) << points[2 * k], points[2 * k + 1], o.phi;

  if (o.avoid && count > 0) {
    // Every size is bounded in floating point before any cast to an integer.
    const double half_d = std::floor(o.span / o.resolution + 1e-9);
    check(half_d <= kMaxHalf, "resolution: too fine for span (more than " + std::to_string(static_cast<long>(2 * kMaxHalf + 1)) +
                                  " orientations)");
    const long half = static_cast<long>(half_d);
    const long m = 2 * half + 1;  // orientation grid, the nominal one in the middle
    // A step of more than m - 1 grid cells reaches nothing more: w <= m - 1 (max_step / resolution
    // may be huge, even inf).
    const double w_d = std::min(std::floor(o.max_step / o.resolution + 1e-9), static_cast<double>(m - 1));
    const long w = std::max(0L, static_cast<long>(w_d));
    const double cells_d = static_cast<double>(count) * m;
    const double bytes = cells_d * (sizeof(Cell) + sizeof(int));
    check(bytes <= kMaxBytes, "points: " + std::to_string(count) + " points x " + std::to_string(m) +
                                  " orientations need " + std::to_string(static_cast<long>(bytes / (1 << 20))) +
                                  " MiB (at most " + std::to_string(static_cast<long>(kMaxBytes / (1 << 20))) +
                                  "); use fewer points, a smaller span or a coarser resolution");
    const double work = cells_d * static_cast<double>(2 * w + 1);
    check(work <= kMaxWork, "max_step: " + std::to_string(count) + " points x " + std::to_string(m) +
                                " orientations x " + std::to_string(2 * w + 1) +
                                " steps exceed the planner's bound (1e9); use a smaller max_step / resolution "
                                "ratio, fewer points or a smaller span");
    auto phi_at = [&](long j) { return o.phi + (j - half) * o.resolution; };

    std::vector<Cell> cells(count * m);
    PartProgress evaluation(progress, 0, 2);  // the grid, then the dynamic programme: half each
    parallel_for(count * m, 2048, [&](long begin, long end) {
      for (long c = begin; c < end; ++c)
        cells[c] = evaluate(robot, Pose(points[2 * (c / m)], points[2 * (c / m) + 1], phi_at(c % m)), o.mode);
    }, progress ? &evaluation : nullptr);

    // Keep the sign of det A at the first point: at the nominal orientation when it is usable,
    // else where the first point is farthest from a parallel singularity.
    const Cell& nominal = cells[half];
    if (nominal.reachable && std::abs(nominal.det_b) >= o.serial_margin) plan.sign = sign_of(nominal.det_a);
    if (plan.sign == 0) {
      double best = -1;
      for (long j = 0; j < m; ++j)
        if (cells[j].reachable && std::abs(cells[j].det_b) >= o.serial_margin && cells[j].distance > best)
          best = cells[j].distance, plan.sign = sign_of(cells[j].det_a);
    }

    auto cost = [&](long k, long j) {
      const Cell& c = cells[k * m + j];
      if (!c.reachable || std::abs(c.det_b) < o.serial_margin || sign_of(c.det_a) != plan.sign) return kForbidden;
      const double dev = phi_at(j) - o.phi, lack = std::max(0.0, o.margin - c.distance);
      return dev * dev + kShortfall * lack * lack;
    };
    std::vector<double> prev(m), cur(m);
    std::vector<int> from(count * m, 0);
    for (long j = 0; j < m; ++j) prev[j] = cost(0, j);
    for (long k = 1; k < count; ++k) {
      report(progress, count + k, 2 * count);
      for (long j = 0; j < m; ++j) {
        double best = std::numeric_limits<double>::infinity();
        for (long i = std::max(0L, j - w), last = std::min(m - 1, j + w); i <= last; ++i) {
          const long d = i - j;
          const double step = d * o.resolution;
          // Ties go to the smallest step, so flat stretches do not wander.
          const double v = prev[i] + o.smoothing * step * step;
          if (v < best || (v == best && std::abs(d) < std::abs(from[k * m + j] - j))) {
            best = v;
            from[k * m + j] = static_cast<int>(i);
          }
        }
        cur[j] = best + cost(k, j);
      }
      std::swap(prev, cur);
    }
    long j = 0;
    for (long i = 1; i < m; ++i)
      if (prev[i] < prev[j] || (prev[i] == prev[j] && std::abs(i - half) < std::abs(j - half))) j = i;
    std::vector<long> path(count);
    for (long k = count - 1; k >= 0; --k) {
      path[k] = j;
      if (k > 0) j = from[k * m + j];
    }
    // Where the margin's boundary wiggles, the optimum follows it up and down: fill every dip of
    // an excursion away from the nominal orientation (ramp, plateau, ramp back) when the filled
    // orientations are as good. The fill keeps the step bound.
    for (long k0 = 0; k0 < count;) {
      const int side = path[k0] > half ? 1 : (path[k0] < half ? -1 : 0);
      long k1 = k0 + 1;
      while (k1 < count && (path[k1] > half ? 1 : (path[k1] < half ? -1 : 0)) == side && side != 0) ++k1;
      if (side != 0) {
        std::vector<long> fill(path.begin() + k0, path.begin() + k1), suffix(fill);
        for (size_t i = 1; i < fill.size(); ++i) fill[i] = side > 0 ? std::max(fill[i], fill[i - 1]) : std::min(fill[i], fill[i - 1]);
        for (size_t i = suffix.size() - 1; i-- > 0;)
          suffix[i] = side > 0 ? std::max(suffix[i], suffix[i + 1]) : std::min(suffix[i], suffix[i + 1]);
        bool better = true;
        for (size_t i = 0; i < fill.size() && better; ++i) {
          fill[i] = side > 0 ? std::min(fill[i], suffix[i]) : std::max(fill[i], suffix[i]);
          const long k = k0 + static_cast<long>(i);
          better = cost(k, fill[i]) < kForbidden &&
                   cells[k * m + fill[i]].distance >= std::min(o.margin, cells[k * m + path[k]].distance);
        }
        if (better) std::copy(fill.begin(), fill.end(), path.begin() + k0);
      }
      k0 = k1;
    }
    for (long k = 0; k < count; ++k) plan.poses(k, 2) = phi_at(path[k]);
  }

  plan.alpha.resize(count, 3);
  plan.det_a_norm.resize(count);
  plan.det_b_norm.resize(count);
  plan.distance.resize(count);
  plan.feasible = count > 0;
  for (long k = 0; k < count; ++k) {
    const Cell c = evaluate(robot, plan.poses.row(k).transpose(), o.mode);
    plan.alpha.row(k) = c.alpha.transpose();
    plan.det_a_norm(k) = c.det_a;
    plan.det_b_norm(k) = c.det_b;
    plan.distance(k) = c.distance;
    if (k == 0 && plan.sign == 0) plan.sign = sign_of(c.det_a);
    const bool step_ok = k == 0 || std::abs(plan.poses(k, 2) - plan.poses(k - 1, 2)) <= o.max_step + 1e-12;
    plan.feasible = plan.feasible && c.reachable && std::abs(c.det_b) >= o.serial_margin &&
                    sign_of(c.det_a) == plan.sign && c.distance >= o.margin && step_ok;
  }
  return plan;
}

}  // namespace robokin
