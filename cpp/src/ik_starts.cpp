// Start configurations for IK's restarts (ik_starts.hpp).
#include "ik_starts.hpp"

#include "chain_lazy.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace robokin {

void random_configuration(const Chain& chain, std::mt19937_64& rng, double* q) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < chain.dof(); ++i) {
    double lo = chain.lower()(i), hi = chain.upper()(i);
    const double span = chain.prismatic(i) ? 1.0 : M_PI;
    if (!std::isfinite(lo) && !std::isfinite(hi)) lo = -span, hi = span;
    else if (!std::isfinite(lo)) lo = hi - 2 * span;
    else if (!std::isfinite(hi)) hi = lo + 2 * span;
    q[i] = lo + (hi - lo) * u(rng);
  }
}

struct IkStarts::Stored {
  explicit Stored(const Chain& chain);
  double distance(const Target& target, int k) const;

  int n;
  std::vector<double> q;  // kCount x n, row-major
  std::vector<Rigid> tools;
  double weight = 1.0;
};

IkStarts::Stored::Stored(const Chain& chain)
    : n(chain.dof()), q(static_cast<std::size_t>(kCount) * n), tools(kCount) {
  std::mt19937_64 rng(0x5eed);
  double reach = 0.0;
  for (int k = 0; k < kCount; ++k) {
    double* qk = q.data() + static_cast<long>(k) * n;
    random_configuration(chain, rng, qk);
    chain.fk(qk, tools[k]);
    reach = std::max(reach, tools[k].p.norm());
  }
  if (std::isfinite(reach) && reach > 0) weight = 0.25 * reach * reach;
}

double IkStarts::Stored::distance(const Target& target, int k) const {
  const Rigid& T = tools[k];
  switch (target.task) {
    case Task::Pose: {
      // 2 (1 - cos angle): angle^2 near 0, increasing with the angle on [0, pi].
      const double c = 0.5 * ((target.pose.R.transpose() * T.R).trace() - 1.0);
      return (T.p - target.pose.p).squaredNorm() + weight * 2.0 * (1.0 - c);
    }
    case Task::Position: return (T.p - target.value).squaredNorm();
    case Task::XY: return (T.p.head<2>() - target.value.head<2>()).squaredNorm();
    case Task::XYPhi: {
      const double a = std::remainder(planar_angle(T) - target.value(2), 2 * M_PI);
      return (T.p.head<2>() - target.value.head<2>()).squaredNorm() + weight * a * a;
    }
  }
  return 0.0;
}

IkStarts::IkStarts(const Chain& chain) : n_(chain.dof()) {
  limits_ = JointLimits{chain.lower(), chain.upper(), {}};
  for (int i = 0; i < n_; ++i) limits_.prismatic.push_back(chain.prismatic(i));
  ClosedArm arm = read_closed_arm(chain);
  if (arm.family.kind != FamilyKind::None) arm_ = std::move(arm);
}

IkStarts::~IkStarts() = default;

const IkStarts::Stored& IkStarts::stored(const Chain& chain) const {
  std::call_once(stored_once_, [&] { stored_ = std::make_unique<const Stored>(chain); });
  return *stored_;
}

const double* IkStarts::q(const Chain& chain, int k) const {
  return stored(chain).q.data() + static_cast<long>(k) * n_;
}

int IkStarts::closed(const Chain& chain, const Target& target, const double* q_ref, double* out) const {
  if (!arm_ || target.task != Task::Pose || !target.pose.p.allFinite() || !target.pose.R.allFinite()) return 0;
  const ClosedFormSolutions s = closed_solve(*arm_, chain, target.pose, limits_);
  double d[ClosedFormSolutions::kMaxSolutions];
  int index[ClosedFormSolutions::kMaxSolutions], count = 0;
  for (int k = 0; k < s.count(); ++k) {
    if (!s.within_limits[k]) continue;
    d[k] = 0.0;
    for (int i = 0; i < n_; ++i) d[k] += (s.row(k)[i] - q_ref[i]) * (s.row(k)[i] - q_ref[i]);
    int j = count++;  // insertion into index, nearest first (at most 8 rows)
    for (; j > 0 && d[index[j - 1]] > d[k]; --j) index[j] = index[j - 1];
    index[j] = k;
  }
  for (int j = 0; j < count; ++j) std::copy(s.row(index[j]), s.row(index[j]) + n_, out + j * n_);
  return count;
}

void IkStarts::nearest(const Chain& chain, const Target& target, int count, int* out) const {
  const Stored& s = stored(chain);
  double d[kCount];
  int index[kCount];
  for (int k = 0; k < kCount; ++k) d[k] = s.distance(target, k), index[k] = k;
  count = std::min(count, kCount);
  // NaN distances (a start whose tool is not finite) sort last.
  const auto closer = [&](int a, int b) { return d[a] < d[b] || (std::isnan(d[b]) && !std::isnan(d[a])); };
  std::partial_sort(index, index + count, index + kCount, closer);
  std::copy(index, index + count, out);
}

const IkStarts& Chain::ik_starts() const {
  std::call_once(lazy_->starts_once, [this] { lazy_->starts = std::make_unique<const IkStarts>(*this); });
  return *lazy_->starts;
}

}  // namespace robokin
