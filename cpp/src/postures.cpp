// The dynamic programme of track_postures (see postures.hpp): forward over the waypoints with
// solutions, each row's best predecessor kept, then back from the best last row.
#include "robokin/postures.hpp"
#include "robokin/angles.hpp"

#include <algorithm>
#include <cmath>

namespace robokin {
namespace {

constexpr double kSlack = 1 + 1e-9;  // the speed limit's allowance for rounding

// The cost of one step between two rows: a reconfiguration (0 or 1) and the motion.
struct StepCost {
  long jump;
  double motion;
};

// The step a -> b (n joints) over `steps` waypoint intervals.
StepCost step_cost(const double* a, const double* b, long n, const double* qdot_max, double dt, long steps,
                   const std::vector<bool>& continuous) {
  StepCost c{0, 0.0};
  for (long i = 0; i < n; ++i) {
    const double d = posture_step(a[i], b[i], continuous[i]);
    if (std::abs(d) > qdot_max[i] * dt * static_cast<double>(steps) * kSlack) c.jump = 1;
    c.motion += d * d;
  }
  c.motion = std::sqrt(c.motion);
  return c;
}

// The programme's state at the last waypoint reached: each row's best (reconfigurations, motion)
// so far.
struct Costs {
  std::vector<long> r;
  std::vector<double> m;
};

// The costs of the first waypoint with solutions: from q0 when given, else 0.
Costs first_costs(const PostureLayer& first, long first_k, long n, const double* qdot_max, double dt,
                  const std::vector<bool>& continuous, const double* q0) {
  Costs c{std::vector<long>(first.count, 0), std::vector<double>(first.count, 0.0)};
  if (!q0) return c;
  for (long b = 0; b < first.count; ++b) {
    const StepCost s = step_cost(q0, first.q + b * n, n, qdot_max, dt, first_k + 1, continuous);
    c.r[b] = s.jump, c.m[b] = s.motion;
  }
  return c;
}

// One layer of the programme: each row of `to` takes its best predecessor in `from` (fewest
// reconfigurations, then least motion, then the lowest row) into back; the new costs.
Costs advance(const Costs& cost, const PostureLayer& from, const PostureLayer& to, long steps, long n,
              const double* qdot_max, double dt, const std::vector<bool>& continuous, std::vector<long>& back) {
  Costs next{std::vector<long>(to.count), std::vector<double>(to.count)};
  back.assign(to.count, 0);
  for (long b = 0; b < to.count; ++b) {
    for (long a = 0; a < from.count; ++a) {
      const StepCost s = step_cost(from.q + a * n, to.q + b * n, n, qdot_max, dt, steps, continuous);
      const long r = cost.r[a] + s.jump;
      const double m = cost.m[a] + s.motion;
      if (a == 0 || r < next.r[b] || (r == next.r[b] && m < next.m[b])) next.r[b] = r, next.m[b] = m, back[b] = a;
    }
  }
  return next;
}

// The best row of the last layer: fewest reconfigurations, then least motion, then the lowest row.
long best_row(const Costs& cost) {
  long best = 0;
  for (long b = 1; b < static_cast<long>(cost.r.size()); ++b)
    if (cost.r[b] < cost.r[best] || (cost.r[b] == cost.r[best] && cost.m[b] < cost.m[best])) best = b;
  return best;
}

// The waypoints the plan's rows enter by a reconfiguration (the steps the programme counted along
// them): from q0 or the previous waypoint with solutions.
void mark_reconfigurations(const std::vector<PostureLayer>& layers, const std::vector<long>& reached, long n,
                           const double* qdot_max, double dt, const std::vector<bool>& continuous, const double* q0,
                           PosturePlan& plan) {
  std::vector<std::int64_t> marked;
  const double* previous = q0;
  long previous_k = -1;
  for (const long k : reached) {
    const double* row = layers[k].q + plan.pick[k] * n;
    if (previous && step_cost(previous, row, n, qdot_max, dt, k - previous_k, continuous).jump) marked.push_back(k);
    previous = row, previous_k = k;
  }
  plan.reconfigured = Eigen::Map<const PosturePlan::Indices>(marked.data(), static_cast<Eigen::Index>(marked.size()));
}

// The joint path of the picked rows (postures.hpp): continuous joints shifted by whole turns towards
// the joints before them where the limits allow, gaps filled with the joints before them, leading
// ones with q0 or else the first solution (zeros when there is none).
void joint_path(const std::vector<PostureLayer>& layers, long n, const std::vector<bool>& continuous,
                const double* q0, const JointLimits& limits, PosturePlan& plan) {
  const long K = static_cast<long>(layers.size());
  const bool limited = limits.lower.size() > 0;
  plan.q = PosturePlan::Joints::Zero(K, n);
  long first = -1;  // the first waypoint with a solution
  const double* last = q0;
  for (long k = 0; k < K; ++k) {
    double* row = plan.q.row(k).data();
    if (plan.pick[k] < 0) {
      if (last) std::copy(last, last + n, row);
      continue;
    }
    const double* v = layers[k].q + plan.pick[k] * n;
    for (long i = 0; i < n; ++i) {
      row[i] = v[i];
      if (!last || !continuous[i]) continue;
      // nearbyint: numpy's round, half to even (the default rounding mode)
      const double shifted = v[i] + 2 * kPi * std::nearbyint((last[i] - v[i]) / (2 * kPi));
      if (!limited || (shifted >= limits.lower[i] && shifted <= limits.upper[i])) row[i] = shifted;
    }
    if (first < 0) first = k;
    last = row;
  }
  if (q0 || first < 0) return;  // leading gaps hold q0 already; no solution: q0 or zeros throughout
  for (long k = 0; k < first; ++k) plan.q.row(k) = plan.q.row(first);
}

}  // namespace

std::vector<std::int64_t> count_reconfigurations(const double* q, long count, long n, const double* qdot_max, double dt,
                                                 const std::vector<bool>& continuous, const double* q0) {
  std::vector<std::int64_t> marked;
  for (long k = 0; k < count; ++k) {
    const double* previous = k ? q + (k - 1) * n : q0;
    if (previous && step_cost(previous, q + k * n, n, qdot_max, dt, 1, continuous).jump) marked.push_back(k);
  }
  return marked;
}

void distinct_rows(const double* q, long count, long n, const std::vector<bool>& continuous, bool* keep) {
  constexpr double kSame = 1e-6;
  for (long r = 0; r < count; ++r) {
    for (long s = 0; keep[r] && s < r; ++s) {
      if (!keep[s]) continue;
      bool same = true;
      for (long i = 0; same && i < n; ++i) same = std::abs(posture_step(q[s * n + i], q[r * n + i], continuous[i])) <= kSame;
      keep[r] = !same;
    }
  }
}

double posture_step(double a, double b, bool continuous) {
  const double d = b - a;
  if (!continuous) return d;
  // numpy's remainder(d + pi, 2 pi): fmod, moved into [0, 2 pi) (the divisor's sign).
  constexpr double kTwoPi = 2 * M_PI;
  double r = std::fmod(d + M_PI, kTwoPi);
  if (r != 0) {
    if (r < 0) r += kTwoPi;
  } else {
    r = 0.0;
  }
  return r - M_PI;
}

PosturePlan track_postures(const std::vector<PostureLayer>& layers, long n, const double* qdot_max, double dt,
                           const std::vector<bool>& continuous, const double* q0, const JointLimits& limits) {
  validate_limits(static_cast<int>(n), limits.lower, limits.upper);  // both empty: no limits
  PosturePlan plan;
  const long K = static_cast<long>(layers.size());
  plan.pick = PosturePlan::Indices::Constant(K, -1);
  std::vector<long> reached;  // the waypoints with solutions, in order
  for (long k = 0; k < K; ++k)
    if (layers[k].count > 0) reached.push_back(k);
  if (reached.empty()) {
    joint_path(layers, n, continuous, q0, limits, plan);
    return plan;
  }
  Costs cost = first_costs(layers[reached[0]], reached[0], n, qdot_max, dt, continuous, q0);
  std::vector<std::vector<long>> back(reached.size());
  for (size_t l = 1; l < reached.size(); ++l) {
    const long a = reached[l - 1], b = reached[l];
    cost = advance(cost, layers[a], layers[b], b - a, n, qdot_max, dt, continuous, back[l]);
  }
  long row = best_row(cost);
  plan.motion = cost.m[row];
  for (size_t l = reached.size(); l-- > 0;) {
    plan.pick[reached[l]] = row;
    if (l > 0) row = back[l][row];
  }
  mark_reconfigurations(layers, reached, n, qdot_max, dt, continuous, q0, plan);
  joint_path(layers, n, continuous, q0, limits, plan);
  return plan;
}

}  // namespace robokin
