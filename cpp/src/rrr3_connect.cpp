// 3-RRR motion between two poses without crossing a parallel singularity: A* in (x, y, phi)
// (see rrr3_connect.hpp).
#include "robokin/rrr3_connect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace robokin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxCells = 2e8;     // the box of grid nodes the search may visit
constexpr long kMaxVisited = 1500000;  // nodes evaluated before the search gives up (memory bound)
constexpr double kNearPenalty = 20;   // cost factor of steps through nodes nearer than the clearance
constexpr int kMaxRepairs = 64;       // A* reruns after an edge found blocked between its nodes
constexpr double kMaxPoses = 1e6;     // poses of an answer (and checks of one segment)

struct Eval {
  double det_a = kNaN, det_b = kNaN, distance = kNaN;
  bool reachable = false;
  int leg = -1;  // the first leg that cannot reach
};

Eval evaluate(const RRR3& robot, const Pose& pose, const Mode& mode, Eigen::Vector3d* alpha_out = nullptr) {
  Eval e;
  Eigen::Vector3d alpha;
  e.leg = robot.ik(pose, mode, alpha.data());
  if (alpha_out) *alpha_out = e.leg >= 0 ? Eigen::Vector3d(Eigen::Vector3d::Constant(kNaN)) : alpha;
  if (e.leg >= 0) return e;
  Eigen::Matrix3d A, B;
  robot.jacobians_at(pose, robot.elbows(alpha), A, B);
  e.reachable = std::isfinite(A.sum()) && std::isfinite(B.sum());
  e.det_a = A.determinant() / robot.platform_radius();
  e.det_b = B.determinant() / std::pow(robot.l1(), 3);
  e.distance = robot.distance(A);
  return e;
}

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

std::string num(double v, const char* fmt = "%.4g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string pose_text(const Pose& p) { return "(" + num(p(0)) + ", " + num(p(1)) + ", " + num(p(2)) + ")"; }

std::string mode_text(const Mode& m) {
  return "(" + std::to_string(m[0]) + ", " + std::to_string(m[1]) + ", " + std::to_string(m[2]) + ")";
}

// What every pose of the path must satisfy.
struct Rules {
  const RRR3* robot;
  Mode mode;
  int sign;
  double clearance, serial_margin;
  // A pose on a segment between ends whose own distance (|det B|) is d_end (b_end): clear of the
  // parallel singularity by min(clearance, d_end), of the serial one by min(serial_margin, b_end).
  bool ok(const Eval& e, double d_end, double b_end) const {
    return e.reachable && sign_of(e.det_a) == sign && e.distance >= std::min(clearance, d_end) &&
           std::abs(e.det_b) >= std::min(serial_margin, b_end);
  }
};

double steps_between_d(const Pose& a, const Pose& b, const RRR3ConnectOptions& o) {
  return std::max({1.0, std::ceil(std::hypot(b(0) - a(0), b(1) - a(1)) / o.max_step),
                   std::ceil(std::abs(b(2) - a(2)) / o.max_turn)});
}

// Steps of the straight segment a -> b; the caller has bounded them by kMaxPoses.
long steps_between(const Pose& a, const Pose& b, const RRR3ConnectOptions& o) {
  return static_cast<long>(std::min(steps_between_d(a, b, o), kMaxPoses));
}

// Poses a + (b - a) t / n, t = 1 .. n (b itself exactly at the end).
Pose along(const Pose& a, const Pose& b, long t, long n) { return t == n ? b : Pose(a + (b - a) * (double(t) / n)); }

}  // namespace

void RRR3ConnectOptions::validate() const {
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  check(clearance >= 0 && clearance < 1, "clearance: must be in [0, 1) (a distance RRR3Singularity.distance)");
  check(serial_margin >= 0 && serial_margin < 1, "serial_margin: must be in [0, 1)");
  check(max_step > 0 && std::isfinite(max_step), "max_step: must be positive and finite");
  check(max_turn > 0 && std::isfinite(max_turn), "max_turn: must be positive and finite");
  check(resolution >= max_step && resolution <= 1000 * max_step, "resolution: must be between max_step and 1000 max_step");
  check(span >= 0 && span <= M_PI, "span: must be in [0, pi]");
  check_mode(mode);
}

RRR3Plan connect(const RRR3& robot, const Pose& start, const Pose& goal, const RRR3ConnectOptions& o,
                 Progress* progress) {
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  check(start.allFinite(), "start: must be finite");
  check(goal.allFinite(), "goal: must be finite");
  o.validate();

  const Eval es = evaluate(robot, start, o.mode), eg = evaluate(robot, goal, o.mode);
  for (int end = 0; end < 2; ++end) {
    const Eval& e = end ? eg : es;
    const std::string name = end ? "goal" : "start";
    const std::string where = name + " " + pose_text(end ? goal : start);
    if (!e.reachable)
      throw NoRoute(name, where + ": leg " + std::to_string(e.leg) + " cannot reach it in working mode " + mode_text(o.mode));
    if (sign_of(e.det_a) == 0 || !(e.distance > 0))
      throw NoRoute(name, where + " is on a parallel singularity (det A = 0) in working mode " + mode_text(o.mode));
    if (!(std::abs(e.det_b) > 0))
      throw NoRoute(name, where + " is on a serial singularity (det B = 0) in working mode " + mode_text(o.mode));
  }
  if (sign_of(es.det_a) != sign_of(eg.det_a))
    throw NoRoute("regions", "start " + pose_text(start) + " (det A / R_e = " + num(es.det_a, "%+.3g") + ") and goal " +
                                 pose_text(goal) + " (det A / R_e = " + num(eg.det_a, "%+.3g") +
                                 ") are in different singularity-free regions of working mode " + mode_text(o.mode) +
                                 ": every path between them crosses a parallel singularity (det A changes sign)");

  const Rules rules{&robot, o.mode, sign_of(es.det_a), o.clearance, o.serial_margin};
  const double d_lo = std::min({o.clearance, es.distance, eg.distance});
  const double b_lo = std::min({o.serial_margin, std::abs(es.det_b), std::abs(eg.det_b)});

  // Checks the straight segment a -> b (a excluded) at the output's spacing.
  auto segment_ok = [&](const Pose& a, const Eval& ea, const Pose& b, const Eval& eb) {
    if (steps_between_d(a, b, o) >= kMaxPoses) return false;  // too long to check: not taken
    const double d_end = std::min(ea.distance, eb.distance), b_end = std::min(std::abs(ea.det_b), std::abs(eb.det_b));
    if (!rules.ok(eb, d_end, b_end)) return false;
    const long n = steps_between(a, b, o);
    for (long t = 1; t < n; ++t)
      if (!rules.ok(evaluate(robot, along(a, b, t, n), o.mode), d_end, b_end)) return false;
    return true;
  };

  // The grid: nodes start + (i h, j h, k hp), within the box every reachable pose lies in.
  const double h = o.resolution, hp = o.resolution * o.max_turn / o.max_step;
  const double reach = robot.base_radius() + robot.l1() + robot.l2() + robot.platform_radius();
  const double phi_lo = std::min(start(2), goal(2)) - o.span, phi_hi = std::max(start(2), goal(2)) + o.span;
  const double i_lo_d = std::floor((-reach - start(0)) / h), i_hi_d = std::ceil((reach - start(0)) / h);
  const double j_lo_d = std::floor((-reach - start(1)) / h), j_hi_d = std::ceil((reach - start(1)) / h);
  const double k_lo_d = std::floor((phi_lo - start(2)) / hp), k_hi_d = std::ceil((phi_hi - start(2)) / hp);
  const double cells = (i_hi_d - i_lo_d + 1) * (j_hi_d - j_lo_d + 1) * (k_hi_d - k_lo_d + 1);
  check(std::isfinite(cells) && cells <= kMaxCells,
        "resolution: too fine for the robot's size and span (" + num(cells, "%.3g") + " grid nodes, at most 2e8)");

  check(steps_between_d(start, goal, o) < kMaxPoses,
        "max_step: start and goal are more than 1e6 steps of max_step (max_turn) apart");

  std::vector<Pose> waypoints;
  std::vector<Eval> wevals;
  if (start == goal) {
    waypoints = {start};
    wevals = {es};
  } else if (segment_ok(start, es, goal, eg)) {
    waypoints = {start, goal};
    wevals = {es, eg};
  } else {
    const long i_lo = long(i_lo_d), j_lo = long(j_lo_d), k_lo = long(k_lo_d);
    const long ni = long(i_hi_d - i_lo_d) + 1, nj = long(j_hi_d - j_lo_d) + 1, nk = long(k_hi_d - k_lo_d) + 1;
    auto index = [&](long i, long j, long k) { return ((k - k_lo) * nj + (j - j_lo)) * ni + (i - i_lo); };
    auto pose_of = [&](long idx) {
      const long i = idx % ni + i_lo, j = (idx / ni) % nj + j_lo, k = idx / (ni * nj) + k_lo;
      return Pose(start(0) + i * h, start(1) + j * h, start(2) + k * hp);
    };
    auto inside = [&](long i, long j, long k) {
      return i >= i_lo && i < i_lo + ni && j >= j_lo && j < j_lo + nj && k >= k_lo && k < k_lo + nk;
    };
    // Node grades: 0 unusable, 1 usable but nearer than the clearance (or the serial margin), 2 clear.
    std::unordered_map<long, Eval> evals;
    auto eval_at = [&](long idx) -> const Eval& {
      auto it = evals.find(idx);
      if (it == evals.end()) it = evals.emplace(idx, evaluate(robot, pose_of(idx), o.mode)).first;
      return it->second;
    };
    auto grade = [&](const Eval& e) {
      if (!rules.ok(e, d_lo, b_lo)) return 0;
      return e.distance >= o.clearance && std::abs(e.det_b) >= o.serial_margin ? 2 : 1;
    };
    auto cost = [&](const Pose& a, const Pose& b) {
      return std::max(std::hypot(b(0) - a(0), b(1) - a(1)) / o.max_step, std::abs(b(2) - a(2)) / o.max_turn);
    };
    const long start_idx = index(0, 0, 0);
    evals.emplace(start_idx, es);
    // Goal's nearest node, and the nodes around it from which a straight segment may reach it.
    const double gi = (goal(0) - start(0)) / h, gj = (goal(1) - start(1)) / h, gk = (goal(2) - start(2)) / hp;
    auto near_goal = [&](long idx) {
      const long i = idx % ni + i_lo, j = (idx / ni) % nj + j_lo, k = idx / (ni * nj) + k_lo;
      return std::abs(i - gi) <= 2 && std::abs(j - gj) <= 2 && std::abs(k - gk) <= 2;
    };
    const long kGoal = -1;
    std::unordered_set<long long> blocked;  // edges (a * cells + b) found blocked between their ends
    auto edge_key = [&](long a, long b) { return static_cast<long long>(a) * static_cast<long long>(ni * nj * nk + 1) + (b + 1); };

    std::vector<long> nodes;  // the last A* answer, start .. node next to the goal
    bool found = false;
    for (int attempt = 0; attempt <= kMaxRepairs && !found; ++attempt) {
      std::unordered_map<long, double> g;
      std::unordered_map<long, long> parent;
      std::unordered_set<long> closed;
      using Item = std::pair<double, long>;
      std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
      g[start_idx] = 0;
      open.push({cost(start, goal), start_idx});
      double goal_g = std::numeric_limits<double>::infinity();
      long goal_parent = -1, expanded = 0;
      while (!open.empty()) {
        const auto [f, idx] = open.top();
        open.pop();
        if (idx == kGoal) break;
        if (!closed.insert(idx).second) continue;
        if (++expanded % 4096 == 0) report(progress, static_cast<long>(evals.size()), kMaxVisited);
        if (static_cast<long>(evals.size()) > kMaxVisited) break;
        const Pose p = pose_of(idx);
        const double gp = g[idx];
        if (near_goal(idx) && !blocked.count(edge_key(idx, kGoal)) && gp + cost(p, goal) < goal_g) {
          if (segment_ok(p, eval_at(idx), goal, eg)) {
            goal_g = gp + cost(p, goal);
            goal_parent = idx;
            open.push({goal_g, kGoal});
          } else {
            blocked.insert(edge_key(idx, kGoal));
          }
        }
        const long i = idx % ni + i_lo, j = (idx / ni) % nj + j_lo, k = idx / (ni * nj) + k_lo;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              if (!(di || dj || dk) || !inside(i + di, j + dj, k + dk)) continue;
              const long n = index(i + di, j + dj, k + dk);
              if (closed.count(n) || blocked.count(edge_key(idx, n))) continue;
              const int gr = grade(eval_at(n));
              if (gr == 0) continue;
              const Pose q = pose_of(n);
              const double gn = gp + cost(p, q) * (gr == 2 ? 1.0 : kNearPenalty);
              auto it = g.find(n);
              if (it != g.end() && it->second <= gn) continue;
              g[n] = gn;
              parent[n] = idx;
              open.push({gn + cost(q, goal), n});
            }
      }
      if (goal_parent < 0) {
        const bool exhausted = static_cast<long>(evals.size()) <= kMaxVisited;
        throw NoRoute("regions",
                      "start " + pose_text(start) + " and goal " + pose_text(goal) +
                          " are in different singularity-free regions of working mode " + mode_text(o.mode) +
                          " at clearance " + num(o.clearance) + ": no path keeps det A / R_e " +
                          (rules.sign > 0 ? "positive" : "negative") + " and clear of parallel singularities " +
                          "with phi in [" + num(phi_lo) + ", " + num(phi_hi) + "]" +
                          (exhausted ? "" : " (the search stopped after " + std::to_string(kMaxVisited) + " poses)"));
      }
      nodes.clear();
      for (long n = goal_parent; n != start_idx; n = parent.at(n)) nodes.push_back(n);
      nodes.push_back(start_idx);
      std::reverse(nodes.begin(), nodes.end());
      // Lazy edge checks: the edges between nodes are checked once a path uses them.
      found = true;
      for (size_t e = 1; e < nodes.size() && found; ++e) {
        if (!segment_ok(pose_of(nodes[e - 1]), eval_at(nodes[e - 1]), pose_of(nodes[e]), eval_at(nodes[e]))) {
          blocked.insert(edge_key(nodes[e - 1], nodes[e]));
          found = false;
        }
      }
    }
    if (!found)
      throw NoRoute("regions", "start " + pose_text(start) + " and goal " + pose_text(goal) +
                                   ": no singularity-free path found on the grid (resolution " + num(o.resolution) +
                                   " m is too coarse here)");
    for (long n : nodes) {
      waypoints.push_back(pose_of(n));
      wevals.push_back(eval_at(n));
    }
    waypoints.front() = start;
    wevals.front() = es;
    waypoints.push_back(goal);
    wevals.push_back(eg);

    // Straight shortcuts: from each kept waypoint, the farthest of the next 1, 2, 4, 8, ...
    // waypoints that a checked straight segment reaches.
    std::vector<Pose> short_w{waypoints.front()};
    std::vector<Eval> short_e{wevals.front()};
    for (size_t a = 0; a + 1 < waypoints.size();) {
      size_t best = a + 1;
      const size_t last = waypoints.size() - 1;
      for (size_t stride = 2; best < last; stride *= 2) {
        const size_t b = std::min(a + stride, last);
        if (!segment_ok(waypoints[a], wevals[a], waypoints[b], wevals[b])) break;
        best = b;
      }
      short_w.push_back(waypoints[best]);
      short_e.push_back(wevals[best]);
      a = best;
    }
    waypoints.swap(short_w);
    wevals.swap(short_e);
  }

  // The output: every segment at the spacing it was checked at.
  double total = 1;
  for (size_t w = 1; w < waypoints.size(); ++w) total += steps_between_d(waypoints[w - 1], waypoints[w], o);
  if (total > kMaxPoses)
    throw NoRoute("regions", "start " + pose_text(start) + " and goal " + pose_text(goal) +
                                 ": the singularity-free path found is longer than 1e6 steps of max_step");
  std::vector<Pose> poses{waypoints.front()};
  for (size_t w = 1; w < waypoints.size(); ++w) {
    const long n = steps_between(waypoints[w - 1], waypoints[w], o);
    for (long t = 1; t <= n; ++t) poses.push_back(along(waypoints[w - 1], waypoints[w], t, n));
  }
  RRR3Plan plan;
  const long count = static_cast<long>(poses.size());
  plan.poses.resize(count, 3);
  plan.alpha.resize(count, 3);
  plan.det_a_norm.resize(count);
  plan.det_b_norm.resize(count);
  plan.distance.resize(count);
  plan.sign = rules.sign;
  plan.feasible = true;
  for (long k = 0; k < count; ++k) {
    Eigen::Vector3d alpha;
    const Eval e = evaluate(robot, poses[k], o.mode, &alpha);
    plan.poses.row(k) = poses[k].transpose();
    plan.alpha.row(k) = alpha.transpose();
    plan.det_a_norm(k) = e.det_a;
    plan.det_b_norm(k) = e.det_b;
    plan.distance(k) = e.distance;
    plan.feasible = plan.feasible && rules.ok(e, d_lo, b_lo);
  }
  if (!plan.feasible)  // cannot happen: every pose was checked on its segment
    throw std::logic_error("RRR3 connect: a checked path failed its own check");
  return plan;
}

}  // namespace robokin
