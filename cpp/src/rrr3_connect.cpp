// 3-RRR motion between two poses without crossing a parallel singularity: A* in (x, y, phi)
// (see rrr3_connect.hpp). The phases: the ends checked (ends), the search box bounded (box_for),
// a straight segment tried, else A* on the grid with its edges checked lazily (GridSearch), the
// answer shortened (shortcut), resampled at the output's spacing (resample) and evaluated
// (plan_along).
#include "robokin/rrr3_connect.hpp"

#include "rrr3_pose_eval.hpp"

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

constexpr double kMaxCells = 2e8;     // the box of grid nodes the search may visit
constexpr long kMaxVisited = 1500000;  // nodes evaluated before the search gives up (memory bound)
constexpr double kNearPenalty = 20;   // cost factor of steps through nodes nearer than the clearance
constexpr int kMaxRepairs = 64;       // A* reruns after an edge found blocked between its nodes
constexpr double kMaxPoses = 1e6;     // poses of an answer (and checks of one segment)

using Eval = PoseEval;

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

void check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

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

// The two ends, evaluated; each usable (reachable, off both singularities) and both with det A of
// one sign, else NoRoute saying which and why.
struct Ends {
  Pose start, goal;
  Eval es, eg;
};

Ends ends(const RRR3& robot, const Pose& start, const Pose& goal, const RRR3ConnectOptions& o) {
  const Ends e{start, goal, evaluate_pose(robot, start, o.mode), evaluate_pose(robot, goal, o.mode)};
  for (int end = 0; end < 2; ++end) {
    const Eval& ev = end ? e.eg : e.es;
    const std::string name = end ? "goal" : "start";
    const std::string where = name + " " + pose_text(end ? goal : start);
    if (!ev.reachable)
      throw NoRoute(name, where + ": leg " + std::to_string(ev.leg) + " cannot reach it in working mode " + mode_text(o.mode));
    if (sign_of(ev.det_a) == 0 || !(ev.distance > 0))
      throw NoRoute(name, where + " is on a parallel singularity (det A = 0) in working mode " + mode_text(o.mode));
    if (!(std::abs(ev.det_b) > 0))
      throw NoRoute(name, where + " is on a serial singularity (det B = 0) in working mode " + mode_text(o.mode));
  }
  if (sign_of(e.es.det_a) != sign_of(e.eg.det_a))
    throw NoRoute("regions", "start " + pose_text(start) + " (det A / R_e = " + num(e.es.det_a, "%+.3g") + ") and goal " +
                                 pose_text(goal) + " (det A / R_e = " + num(e.eg.det_a, "%+.3g") +
                                 ") are in different singularity-free regions of working mode " + mode_text(o.mode) +
                                 ": every path between them crosses a parallel singularity (det A changes sign)");
  return e;
}

// The checks of straight segments between poses: the rules at the output's spacing, the ends'
// own distances (d_lo, b_lo) as the floors of the whole path.
struct Segments {
  const RRR3& robot;
  const RRR3ConnectOptions& o;
  Rules rules;
  double d_lo, b_lo;

  // The straight segment a -> b (a excluded) at the output's spacing.
  bool ok(const Pose& a, const Eval& ea, const Pose& b, const Eval& eb) const {
    if (steps_between_d(a, b, o) >= kMaxPoses) return false;  // too long to check: not taken
    const double d_end = std::min(ea.distance, eb.distance), b_end = std::min(std::abs(ea.det_b), std::abs(eb.det_b));
    if (!rules.ok(eb, d_end, b_end)) return false;
    const long n = steps_between(a, b, o);
    for (long t = 1; t < n; ++t)
      if (!rules.ok(evaluate_pose(robot, along(a, b, t, n), o.mode), d_end, b_end)) return false;
    return true;
  }
};

Segments segments_for(const RRR3& robot, const Ends& e, const RRR3ConnectOptions& o) {
  return Segments{robot, o, Rules{o.mode, sign_of(e.es.det_a), o.clearance, o.serial_margin},
                  std::min({o.clearance, e.es.distance, e.eg.distance}),
                  std::min({o.serial_margin, std::abs(e.es.det_b), std::abs(e.eg.det_b)})};
}

// The grid: nodes start + (i h, j h, k hp), within the box every reachable pose lies in (index
// bounds as doubles, bounded before any cast) and phi in [phi_lo, phi_hi].
struct Box {
  double h, hp, phi_lo, phi_hi;
  double i_lo_d, i_hi_d, j_lo_d, j_hi_d, k_lo_d, k_hi_d;
};

Box box_for(const RRR3& robot, const Pose& start, const Pose& goal, const RRR3ConnectOptions& o) {
  Box b;
  b.h = o.resolution, b.hp = o.resolution * o.max_turn / o.max_step;
  const double reach = robot.base_radius() + robot.l1() + robot.l2() + robot.platform_radius();
  b.phi_lo = std::min(start(2), goal(2)) - o.span, b.phi_hi = std::max(start(2), goal(2)) + o.span;
  b.i_lo_d = std::floor((-reach - start(0)) / b.h), b.i_hi_d = std::ceil((reach - start(0)) / b.h);
  b.j_lo_d = std::floor((-reach - start(1)) / b.h), b.j_hi_d = std::ceil((reach - start(1)) / b.h);
  b.k_lo_d = std::floor((b.phi_lo - start(2)) / b.hp), b.k_hi_d = std::ceil((b.phi_hi - start(2)) / b.hp);
  const double cells = (b.i_hi_d - b.i_lo_d + 1) * (b.j_hi_d - b.j_lo_d + 1) * (b.k_hi_d - b.k_lo_d + 1);
  check(std::isfinite(cells) && cells <= kMaxCells,
        "resolution: too fine for the robot's size and span (" + num(cells, "%.3g") + " grid nodes, at most 2e8)");
  return b;
}

// A* over the grid from the start's node to the goal (reached by a checked straight segment from a
// node near it), nodes evaluated once and cached; edges are checked once a path uses them, and
// A* runs again without the blocked ones.
class GridSearch {
 public:
  GridSearch(const Ends& e, const Box& box, const Segments& seg, Progress* progress)
      : e_(e), b_(box), seg_(seg), o_(seg.o), progress_(progress) {
    i_lo_ = long(b_.i_lo_d), j_lo_ = long(b_.j_lo_d), k_lo_ = long(b_.k_lo_d);
    ni_ = long(b_.i_hi_d - b_.i_lo_d) + 1, nj_ = long(b_.j_hi_d - b_.j_lo_d) + 1, nk_ = long(b_.k_hi_d - b_.k_lo_d) + 1;
    start_idx_ = index(0, 0, 0);
    evals_.emplace(start_idx_, e_.es);
    gi_ = (e_.goal(0) - e_.start(0)) / b_.h, gj_ = (e_.goal(1) - e_.start(1)) / b_.h;
    gk_ = (e_.goal(2) - e_.start(2)) / b_.hp;
  }

  // The waypoints start, grid nodes, goal, with their evaluations; NoRoute when there is none.
  void waypoints(std::vector<Pose>& poses, std::vector<Eval>& evals) {
    const std::vector<long> nodes = repaired_path();
    for (long n : nodes) {
      poses.push_back(pose_of(n));
      evals.push_back(eval_at(n));
    }
    poses.front() = e_.start;
    evals.front() = e_.es;
    poses.push_back(e_.goal);
    evals.push_back(e_.eg);
  }

 private:
  static constexpr long kGoal = -1;

  long index(long i, long j, long k) const { return ((k - k_lo_) * nj_ + (j - j_lo_)) * ni_ + (i - i_lo_); }
  void coords(long idx, long& i, long& j, long& k) const {
    i = idx % ni_ + i_lo_, j = (idx / ni_) % nj_ + j_lo_, k = idx / (ni_ * nj_) + k_lo_;
  }
  Pose pose_of(long idx) const {
    long i, j, k;
    coords(idx, i, j, k);
    return Pose(e_.start(0) + i * b_.h, e_.start(1) + j * b_.h, e_.start(2) + k * b_.hp);
  }
  bool inside(long i, long j, long k) const {
    return i >= i_lo_ && i < i_lo_ + ni_ && j >= j_lo_ && j < j_lo_ + nj_ && k >= k_lo_ && k < k_lo_ + nk_;
  }
  const Eval& eval_at(long idx) {
    auto it = evals_.find(idx);
    if (it == evals_.end()) it = evals_.emplace(idx, evaluate_pose(seg_.robot, pose_of(idx), o_.mode)).first;
    return it->second;
  }
  // Node grades: 0 unusable, 1 usable but nearer than the clearance (or the serial margin), 2 clear.
  int grade(const Eval& e) const {
    if (!seg_.rules.ok(e, seg_.d_lo, seg_.b_lo)) return 0;
    return e.distance >= o_.clearance && std::abs(e.det_b) >= o_.serial_margin ? 2 : 1;
  }
  double cost(const Pose& a, const Pose& b) const {
    return std::max(std::hypot(b(0) - a(0), b(1) - a(1)) / o_.max_step, std::abs(b(2) - a(2)) / o_.max_turn);
  }
  // The nodes from which a straight segment may reach the goal: within 2 cells of it.
  bool near_goal(long idx) const {
    long i, j, k;
    coords(idx, i, j, k);
    return std::abs(i - gi_) <= 2 && std::abs(j - gj_) <= 2 && std::abs(k - gk_) <= 2;
  }
  // Edges (a * cells + b) found blocked between their ends.
  long long edge_key(long a, long b) const {
    return static_cast<long long>(a) * static_cast<long long>(ni_ * nj_ * nk_ + 1) + (b + 1);
  }

  // A* answers until one has every edge clear: start .. the node next to the goal.
  std::vector<long> repaired_path() {
    std::vector<long> nodes;
    bool found = false;
    for (int attempt = 0; attempt <= kMaxRepairs && !found; ++attempt) {
      nodes = astar();
      found = edges_clear(nodes);
    }
    if (!found)
      throw NoRoute("regions", "start " + pose_text(e_.start) + " and goal " + pose_text(e_.goal) +
                                   ": no singularity-free path found on the grid (resolution " + num(o_.resolution) +
                                   " m is too coarse here)");
    return nodes;
  }

  // Lazy edge checks: the first blocked edge of nodes is recorded; true when there is none.
  bool edges_clear(const std::vector<long>& nodes) {
    for (size_t e = 1; e < nodes.size(); ++e) {
      if (!seg_.ok(pose_of(nodes[e - 1]), eval_at(nodes[e - 1]), pose_of(nodes[e]), eval_at(nodes[e]))) {
        blocked_.insert(edge_key(nodes[e - 1], nodes[e]));
        return false;
      }
    }
    return true;
  }

  // One A* run without the blocked edges: the nodes start .. the goal's parent; NoRoute when the
  // goal is not reached.
  std::vector<long> astar() {
    g_.clear(), parent_.clear(), closed_.clear();
    open_ = Queue();
    g_[start_idx_] = 0;
    open_.push({cost(e_.start, e_.goal), start_idx_});
    goal_g_ = std::numeric_limits<double>::infinity();
    goal_parent_ = -1;
    long expanded = 0;
    while (!open_.empty()) {
      const auto [f, idx] = open_.top();
      open_.pop();
      if (idx == kGoal) break;
      if (!closed_.insert(idx).second) continue;
      if (++expanded % 4096 == 0) report(progress_, static_cast<long>(evals_.size()), kMaxVisited);
      if (static_cast<long>(evals_.size()) > kMaxVisited) break;
      expand(idx);
    }
    if (goal_parent_ < 0) throw_unreached();
    std::vector<long> nodes;
    for (long n = goal_parent_; n != start_idx_; n = parent_.at(n)) nodes.push_back(n);
    nodes.push_back(start_idx_);
    std::reverse(nodes.begin(), nodes.end());
    return nodes;
  }

  // A* step at idx: the goal when a checked segment reaches it, then the 26 neighbours.
  void expand(long idx) {
    const Pose p = pose_of(idx);
    const double gp = g_[idx];
    if (near_goal(idx) && !blocked_.count(edge_key(idx, kGoal)) && gp + cost(p, e_.goal) < goal_g_) {
      if (seg_.ok(p, eval_at(idx), e_.goal, e_.eg)) {
        goal_g_ = gp + cost(p, e_.goal);
        goal_parent_ = idx;
        open_.push({goal_g_, kGoal});
      } else {
        blocked_.insert(edge_key(idx, kGoal));
      }
    }
    long i, j, k;
    coords(idx, i, j, k);
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (!(di || dj || dk) || !inside(i + di, j + dj, k + dk)) continue;
          const long n = index(i + di, j + dj, k + dk);
          if (closed_.count(n) || blocked_.count(edge_key(idx, n))) continue;
          const int gr = grade(eval_at(n));
          if (gr == 0) continue;
          const Pose q = pose_of(n);
          const double gn = gp + cost(p, q) * (gr == 2 ? 1.0 : kNearPenalty);
          auto it = g_.find(n);
          if (it != g_.end() && it->second <= gn) continue;
          g_[n] = gn;
          parent_[n] = idx;
          open_.push({gn + cost(q, e_.goal), n});
        }
  }

  [[noreturn]] void throw_unreached() const {
    const bool exhausted = static_cast<long>(evals_.size()) <= kMaxVisited;
    throw NoRoute("regions",
                  "start " + pose_text(e_.start) + " and goal " + pose_text(e_.goal) +
                      " are in different singularity-free regions of working mode " + mode_text(o_.mode) +
                      " at clearance " + num(o_.clearance) + ": no path keeps det A / R_e " +
                      (seg_.rules.sign > 0 ? "positive" : "negative") + " and clear of parallel singularities " +
                      "with phi in [" + num(b_.phi_lo) + ", " + num(b_.phi_hi) + "]" +
                      (exhausted ? "" : " (the search stopped after " + std::to_string(kMaxVisited) + " poses)"));
  }

  using Item = std::pair<double, long>;
  using Queue = std::priority_queue<Item, std::vector<Item>, std::greater<Item>>;

  const Ends& e_;
  const Box& b_;
  const Segments& seg_;
  const RRR3ConnectOptions& o_;
  Progress* progress_;
  long i_lo_, j_lo_, k_lo_, ni_, nj_, nk_, start_idx_;
  double gi_, gj_, gk_;  // the goal in grid units
  std::unordered_map<long, Eval> evals_;
  std::unordered_set<long long> blocked_;
  // One A* run's state.
  std::unordered_map<long, double> g_;
  std::unordered_map<long, long> parent_;
  std::unordered_set<long> closed_;
  Queue open_;
  double goal_g_ = 0;
  long goal_parent_ = -1;
};

// Straight shortcuts: from each kept waypoint, the farthest of the next 1, 2, 4, 8, ... waypoints
// that a checked straight segment reaches.
void shortcut(const Segments& seg, std::vector<Pose>& waypoints, std::vector<Eval>& wevals) {
  std::vector<Pose> short_w{waypoints.front()};
  std::vector<Eval> short_e{wevals.front()};
  for (size_t a = 0; a + 1 < waypoints.size();) {
    size_t best = a + 1;
    const size_t last = waypoints.size() - 1;
    for (size_t stride = 2; best < last; stride *= 2) {
      const size_t b = std::min(a + stride, last);
      if (!seg.ok(waypoints[a], wevals[a], waypoints[b], wevals[b])) break;
      best = b;
    }
    short_w.push_back(waypoints[best]);
    short_e.push_back(wevals[best]);
    a = best;
  }
  waypoints.swap(short_w);
  wevals.swap(short_e);
}

// The output's poses: every segment at the spacing it was checked at (at most kMaxPoses).
std::vector<Pose> resample(const std::vector<Pose>& waypoints, const Ends& e, const RRR3ConnectOptions& o) {
  double total = 1;
  for (size_t w = 1; w < waypoints.size(); ++w) total += steps_between_d(waypoints[w - 1], waypoints[w], o);
  if (total > kMaxPoses)
    throw NoRoute("regions", "start " + pose_text(e.start) + " and goal " + pose_text(e.goal) +
                                 ": the singularity-free path found is longer than 1e6 steps of max_step");
  std::vector<Pose> poses{waypoints.front()};
  for (size_t w = 1; w < waypoints.size(); ++w) {
    const long n = steps_between(waypoints[w - 1], waypoints[w], o);
    for (long t = 1; t <= n; ++t) poses.push_back(along(waypoints[w - 1], waypoints[w], t, n));
  }
  return poses;
}

// The plan along poses, every pose evaluated again (a checked path: feasible by construction).
RRR3Plan plan_along(const std::vector<Pose>& poses, const Segments& seg) {
  RRR3Plan plan;
  const long count = static_cast<long>(poses.size());
  plan.poses.resize(count, 3);
  plan.alpha.resize(count, 3);
  plan.det_a_norm.resize(count);
  plan.det_b_norm.resize(count);
  plan.distance.resize(count);
  plan.sign = seg.rules.sign;
  plan.feasible = true;
  for (long k = 0; k < count; ++k) {
    const Eval e = evaluate_pose(seg.robot, poses[k], seg.o.mode);
    plan.poses.row(k) = poses[k].transpose();
    plan.alpha.row(k) = e.alpha.transpose();
    plan.det_a_norm(k) = e.det_a;
    plan.det_b_norm(k) = e.det_b;
    plan.distance(k) = e.distance;
    plan.feasible = plan.feasible && seg.rules.ok(e, seg.d_lo, seg.b_lo);
  }
  if (!plan.feasible)  // cannot happen: every pose was checked on its segment
    throw std::logic_error("RRR3 connect: a checked path failed its own check");
  return plan;
}

}  // namespace

void RRR3ConnectOptions::validate() const {
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
  check(start.allFinite(), "start: must be finite");
  check(goal.allFinite(), "goal: must be finite");
  o.validate();
  const Ends e = ends(robot, start, goal, o);
  const Segments seg = segments_for(robot, e, o);
  const Box box = box_for(robot, start, goal, o);
  check(steps_between_d(start, goal, o) < kMaxPoses,
        "max_step: start and goal are more than 1e6 steps of max_step (max_turn) apart");
  std::vector<Pose> waypoints;
  std::vector<Eval> wevals;
  if (start == goal) {
    waypoints = {start};
    wevals = {e.es};
  } else if (seg.ok(start, e.es, goal, e.eg)) {
    waypoints = {start, goal};
    wevals = {e.es, e.eg};
  } else {
    GridSearch(e, box, seg, progress).waypoints(waypoints, wevals);
    shortcut(seg, waypoints, wevals);
  }
  return plan_along(resample(waypoints, e, o), seg);
}

}  // namespace robokin
