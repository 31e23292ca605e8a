// 3-RRR path planning with parallel-singularity avoidance: dynamic programming over a grid of
// orientations, and the closing of a loop (see rrr3_plan.hpp).
#include "robokin/rrr3_plan.hpp"

#include "robokin/parallel.hpp"

#include "rrr3_pose_eval.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>
#include <stdexcept>

namespace robokin {
namespace {

constexpr double kForbidden = 1e12;  // cost of an unreachable, serial or wrong-sign orientation
constexpr double kShortfall = 1e8;   // weight of (margin - distance)^2 below the margin: nearly a constraint
constexpr double kMaxHalf = 1e5;     // orientations on each side of the nominal one
constexpr double kMaxBytes = 1024.0 * 1024 * 1024;  // memory of the grid (cells and back pointers)
constexpr double kMaxWork = 1e9;     // count * m * (2 w + 1) transitions of the dynamic programme
constexpr double kStepSlack = 1e-12;  // rounding allowed on an orientation step's bound

// The model at one (point, orientation): the shared evaluation (rrr3_pose_eval.hpp).
using Cell = PoseEval;

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

void check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// The orientation grid of the avoidance: m = 2 half + 1 orientations phi + (j - half) resolution,
// the nominal one in the middle, and steps of at most w cells between consecutive points.
struct Grid {
  long half = 0, m = 1, w = 0;
  double phi = 0, resolution = 0;
  double at(long j) const { return phi + (j - half) * resolution; }
};

// The grid for count points, its memory and work bounded before anything is allocated.
Grid grid_for(long count, const RRR3PlanOptions& o) {
  // Every size is bounded in floating point before any cast to an integer.
  const double half_d = std::floor(o.span / o.resolution + 1e-9);
  check(half_d <= kMaxHalf, "resolution: too fine for span (more than " + std::to_string(static_cast<long>(2 * kMaxHalf + 1)) +
                                " orientations)");
  Grid g;
  g.phi = o.phi;
  g.resolution = o.resolution;
  g.half = static_cast<long>(half_d);
  g.m = 2 * g.half + 1;
  // A step of more than m - 1 grid cells reaches nothing more: w <= m - 1 (max_step / resolution
  // may be huge, even inf).
  const double w_d = std::min(std::floor(o.max_step / o.resolution + 1e-9), static_cast<double>(g.m - 1));
  g.w = std::max(0L, static_cast<long>(w_d));
  const double cells_d = static_cast<double>(count) * g.m;
  const double bytes = cells_d * (sizeof(Cell) + sizeof(int));
  check(bytes <= kMaxBytes, "points: " + std::to_string(count) + " points x " + std::to_string(g.m) +
                                " orientations need " + std::to_string(static_cast<long>(bytes / (1 << 20))) +
                                " MiB (at most " + std::to_string(static_cast<long>(kMaxBytes / (1 << 20))) +
                                "); use fewer points, a smaller span or a coarser resolution");
  const double work = cells_d * static_cast<double>(2 * g.w + 1);
  check(work <= kMaxWork, "max_step: " + std::to_string(count) + " points x " + std::to_string(g.m) +
                              " orientations x " + std::to_string(2 * g.w + 1) +
                              " steps exceed the planner's bound (1e9); use a smaller max_step / resolution "
                              "ratio, fewer points or a smaller span");
  return g;
}

// The model at every (point, grid orientation), point-major.
std::vector<Cell> evaluate_grid(const RRR3& robot, const double* points, long count, const Grid& g, const Mode& mode,
                                Progress* progress) {
  std::vector<Cell> cells(count * g.m);
  parallel_for(count * g.m, 2048, [&](long begin, long end) {
    for (long c = begin; c < end; ++c)
      cells[c] = evaluate_pose(robot, Pose(points[2 * (c / g.m)], points[2 * (c / g.m) + 1], g.at(c % g.m)), mode);
  }, progress);
  return cells;
}

// The sign of det A to keep: the first point's at the nominal orientation when it is usable, else
// where the first point is farthest from a parallel singularity (0 when no orientation is usable).
int choose_sign(const std::vector<Cell>& cells, const Grid& g, double serial_margin) {
  const Cell& nominal = cells[g.half];
  if (nominal.reachable && std::abs(nominal.det_b) >= serial_margin && sign_of(nominal.det_a) != 0)
    return sign_of(nominal.det_a);
  int sign = 0;
  double best = -1;
  for (long j = 0; j < g.m; ++j)
    if (cells[j].reachable && std::abs(cells[j].det_b) >= serial_margin && cells[j].distance > best)
      best = cells[j].distance, sign = sign_of(cells[j].det_a);
  return sign;
}

// The grid index of each point's orientation minimising the summed cost(k, j) plus smoothing
// times the squared steps, steps at most w cells (dynamic programming, ties to the smallest step
// and, at the end, to the orientation nearest the nominal one).
template <class Cost>
std::vector<long> programme(long count, const Grid& g, double smoothing, const Cost& cost, Progress* progress) {
  const long m = g.m;
  std::vector<double> prev(m), cur(m);
  std::vector<int> from(count * m, 0);
  for (long j = 0; j < m; ++j) prev[j] = cost(0, j);
  for (long k = 1; k < count; ++k) {
    report(progress, count + k, 2 * count);
    for (long j = 0; j < m; ++j) {
      double best = std::numeric_limits<double>::infinity();
      for (long i = std::max(0L, j - g.w), last = std::min(m - 1, j + g.w); i <= last; ++i) {
        const long d = i - j;
        const double step = d * g.resolution;
        // Ties go to the smallest step, so flat stretches do not wander.
        const double v = prev[i] + smoothing * step * step;
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
    if (prev[i] < prev[j] || (prev[i] == prev[j] && std::abs(i - g.half) < std::abs(j - g.half))) j = i;
  std::vector<long> path(count);
  for (long k = count - 1; k >= 0; --k) {
    path[k] = j;
    if (k > 0) j = from[k * m + j];
  }
  return path;
}

// Where the margin's boundary wiggles, the optimum follows it up and down: fill every dip of an
// excursion away from the nominal orientation (ramp, plateau, ramp back) when the filled
// orientations are as good. The fill keeps the step bound.
template <class Cost>
void fill_dips(std::vector<long>& path, const std::vector<Cell>& cells, const Grid& g, double margin, const Cost& cost) {
  const long count = static_cast<long>(path.size()), half = g.half, m = g.m;
  auto side_of = [half](long j) { return j > half ? 1 : (j < half ? -1 : 0); };
  for (long k0 = 0; k0 < count;) {
    const int side = side_of(path[k0]);
    long k1 = k0 + 1;
    while (k1 < count && side_of(path[k1]) == side && side != 0) ++k1;
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
                 cells[k * m + fill[i]].distance >= std::min(margin, cells[k * m + path[k]].distance);
      }
      if (better) std::copy(fill.begin(), fill.end(), path.begin() + k0);
    }
    k0 = k1;
  }
}

// The avoidance orientations of an open path into plan.poses' third column, and the sign kept.
void avoid_open(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& o, Progress* progress,
                RRR3Plan& plan) {
  const Grid g = grid_for(count, o);
  PartProgress evaluation(progress, 0, 2);  // the grid, then the dynamic programme: half each
  const std::vector<Cell> cells = evaluate_grid(robot, points, count, g, o.mode, progress ? &evaluation : nullptr);
  plan.sign = choose_sign(cells, g, o.serial_margin);
  auto cost = [&](long k, long j) {
    const Cell& c = cells[k * g.m + j];
    if (!c.reachable || std::abs(c.det_b) < o.serial_margin || sign_of(c.det_a) != plan.sign) return kForbidden;
    const double dev = g.at(j) - o.phi, lack = std::max(0.0, o.margin - c.distance);
    return dev * dev + kShortfall * lack * lack;
  };
  std::vector<long> path = programme(count, g, o.smoothing, cost, progress);
  fill_dips(path, cells, g, o.margin, cost);
  for (long k = 0; k < count; ++k) plan.poses(k, 2) = g.at(path[k]);
}

// The model along plan.poses, and whether the plan is feasible (for a closed path with its join).
void evaluate_along(const RRR3& robot, const RRR3PlanOptions& o, RRR3Plan& plan) {
  const long count = plan.poses.rows();
  plan.alpha.resize(count, 3);
  plan.det_a_norm.resize(count);
  plan.det_b_norm.resize(count);
  plan.distance.resize(count);
  plan.feasible = count > 0;
  for (long k = 0; k < count; ++k) {
    const Cell c = evaluate_pose(robot, plan.poses.row(k).transpose(), o.mode);
    plan.alpha.row(k) = c.alpha.transpose();
    plan.det_a_norm(k) = c.det_a;
    plan.det_b_norm(k) = c.det_b;
    plan.distance(k) = c.distance;
    if (k == 0 && plan.sign == 0) plan.sign = sign_of(c.det_a);
    const long before = k > 0 ? k - 1 : (o.closed ? count - 1 : 0);
    const bool step_ok = std::abs(plan.poses(k, 2) - plan.poses(before, 2)) <= o.max_step + kStepSlack;
    plan.feasible = plan.feasible && c.reachable && std::abs(c.det_b) >= o.serial_margin &&
                    sign_of(c.det_a) == plan.sign && c.distance >= o.margin && step_ok;
  }
}

// The plan of the path as given (closed only decides whether the join counts for `feasible`).
RRR3Plan open_plan(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& o, Progress* progress) {
  RRR3Plan plan;
  plan.poses.resize(count, 3);
  for (long k = 0; k < count; ++k) plan.poses.row(k) << points[2 * k], points[2 * k + 1], o.phi;
  if (o.avoid && count > 0) avoid_open(robot, points, count, o, progress, plan);
  evaluate_along(robot, o, plan);
  return plan;
}

// The point of the loop clearest of parallel singularities at the nominal orientation, among those
// with det A of the first point's sign there; -1 when there is none (the first is unreachable).
long clearest_point(const RRR3Plan& nominal) {
  long cut = -1;
  double best = -1;
  if (nominal.poses.rows() == 0 || !std::isfinite(nominal.det_a_norm(0))) return cut;
  const int first = sign_of(nominal.det_a_norm(0));
  for (long k = 0; k < nominal.poses.rows(); ++k)
    if (std::isfinite(nominal.distance(k)) && sign_of(nominal.det_a_norm(k)) == first && nominal.distance(k) > best)
      best = nominal.distance(k), cut = k;
  return cut;
}

// A closed path with avoidance: the plan of the loop cut where it is clearest (see rrr3_plan.hpp).
RRR3Plan closed_plan(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& o, Progress* progress) {
  RRR3PlanOptions open = o;
  open.closed = false;
  PartProgress direct_part(progress, 0, 3), nominal_part(progress, 1, 3), rolled_part(progress, 2, 3);
  RRR3Plan direct = open_plan(robot, points, count, open, progress ? &direct_part : nullptr);
  open.avoid = false;
  const long cut = clearest_point(open_plan(robot, points, count, open, progress ? &nominal_part : nullptr));
  open.avoid = true;
  if (cut >= 0) {
    std::vector<double> rolled(2 * count);
    for (long k = 0; k < count; ++k) {
      rolled[2 * k] = points[2 * ((k + cut) % count)];
      rolled[2 * k + 1] = points[2 * ((k + cut) % count) + 1];
    }
    const RRR3Plan r = open_plan(robot, rolled.data(), count, open, progress ? &rolled_part : nullptr);
    const double join = std::abs(r.poses(0, 2) - r.poses(count - 1, 2));  // between points cut - 1 and cut
    if (r.feasible && join <= o.max_step + kStepSlack) {
      RRR3Plan plan;
      plan.poses.resize(count, 3);
      for (long k = 0; k < count; ++k)
        plan.poses.row(k) << points[2 * k], points[2 * k + 1], r.poses((k - cut + count) % count, 2);
      plan.sign = r.sign;
      evaluate_along(robot, o, plan);
      return plan;
    }
  }
  evaluate_along(robot, o, direct);  // the join now counts
  return direct;
}

}  // namespace

void RRR3PlanOptions::validate() const {
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
  check(count >= 0, "points: negative count");
  o.validate();
  if (o.closed && o.avoid && count > 1) return closed_plan(robot, points, count, o, progress);
  return open_plan(robot, points, count, o, progress);
}

}  // namespace robokin
