// Start configurations for IK's restarts (ik_starts.hpp).
#include "ik_starts.hpp"

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

IkStarts::IkStarts(const Chain& chain) : n_(chain.dof()), q_(static_cast<std::size_t>(kCount) * n_), tools_(kCount) {
  std::mt19937_64 rng(0x5eed);
  double reach = 0.0;
  for (int k = 0; k < kCount; ++k) {
    double* qk = q_.data() + static_cast<long>(k) * n_;
    random_configuration(chain, rng, qk);
    chain.fk(qk, tools_[k]);
    reach = std::max(reach, tools_[k].p.norm());
  }
  if (std::isfinite(reach) && reach > 0) weight_ = 0.25 * reach * reach;
  limits_ = JointLimits{chain.lower(), chain.upper(), {}};
  for (int i = 0; i < n_; ++i) limits_.prismatic.push_back(chain.prismatic(i));
  ClosedArm arm{joint_axes(chain), {}};
  arm.family = closed_family(arm.axes);
  if (arm.family.kind != FamilyKind::None) arm_ = std::move(arm);
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
    index[count++] = k;
  }
  std::sort(index, index + count, [&](int a, int b) { return d[a] < d[b]; });
  for (int j = 0; j < count; ++j) std::copy(s.row(index[j]), s.row(index[j]) + n_, out + j * n_);
  return count;
}

double IkStarts::distance(const Target& target, int k) const {
  const Rigid& T = tools_[k];
  switch (target.task) {
    case Task::Pose: {
      // 2 (1 - cos angle): angle^2 near 0, increasing with the angle on [0, pi].
      const double c = 0.5 * ((target.pose.R.transpose() * T.R).trace() - 1.0);
      return (T.p - target.pose.p).squaredNorm() + weight_ * 2.0 * (1.0 - c);
    }
    case Task::Position: return (T.p - target.value).squaredNorm();
    case Task::XY: return (T.p.head<2>() - target.value.head<2>()).squaredNorm();
    case Task::XYPhi: {
      const double a = std::remainder(planar_angle(T) - target.value(2), 2 * M_PI);
      return (T.p.head<2>() - target.value.head<2>()).squaredNorm() + weight_ * a * a;
    }
  }
  return 0.0;
}

void IkStarts::nearest(const Target& target, int count, int* out) const {
  double d[kCount];
  int index[kCount];
  for (int k = 0; k < kCount; ++k) d[k] = distance(target, k), index[k] = k;
  count = std::min(count, kCount);
  // NaN distances (a start whose tool is not finite) sort last.
  const auto closer = [&](int a, int b) { return d[a] < d[b] || (std::isnan(d[b]) && !std::isnan(d[a])); };
  std::partial_sort(index, index + count, index + kCount, closer);
  std::copy(index, index + count, out);
}

const IkStarts& Chain::ik_starts() const {
  std::call_once(lazy_->once, [this] { lazy_->starts = std::make_unique<const IkStarts>(*this); });
  return *lazy_->starts;
}

}  // namespace robokin
