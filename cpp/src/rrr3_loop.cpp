// 3-RRR loops on one side of the parallel singularities: the search over nominal orientations
// (see rrr3_loop.hpp).
#include "robokin/rrr3_loop.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

constexpr long kMaxNominals = 10000;  // each costs up to three plans of the loop

int sign_of(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

void check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

}  // namespace

std::vector<double> default_nominals() {
  std::vector<double> nominals{0.0};
  for (int k = 1; k <= 30; ++k) {
    nominals.push_back(k / 20.0);  // the double nearest k * 0.05
    nominals.push_back(-k / 20.0);
  }
  return nominals;
}

void RRR3LoopOptions::validate() const {
  check(sign == 1 || sign == -1, "sign: must be +1 or -1, got " + std::to_string(sign));
  check(!nominals.empty(), "nominals: must hold at least one orientation");
  check(static_cast<long>(nominals.size()) <= kMaxNominals,
        "nominals: at most " + std::to_string(kMaxNominals) + " orientations, got " + std::to_string(nominals.size()));
  for (double phi : nominals) check(std::isfinite(phi), "nominals: every orientation must be finite");
}

RRR3Loop plan_loop(const RRR3& robot, const double* points, long count, const RRR3PlanOptions& plan,
                   const RRR3LoopOptions& loop, Progress* progress) {
  check(count >= 0, "points: negative count");
  loop.validate();
  RRR3PlanOptions o = plan;
  o.closed = true;
  o.phi = loop.nominals.front();
  o.validate();
  RRR3Loop result, fallback;
  bool started = false;  // some nominal had the first point on the side
  const long parts = static_cast<long>(loop.nominals.size());
  for (long i = 0; i < parts; ++i) {
    report(progress, i, parts);
    o.phi = loop.nominals[i];
    RRR3PlanOptions constant = o;
    constant.avoid = false;
    RRR3Plan nominal = plan_path(robot, points, count, constant);
    if (count == 0 || !std::isfinite(nominal.det_a_norm(0)) || sign_of(nominal.det_a_norm(0)) != loop.sign) continue;
    started = true;
    if (!o.avoid) {
      bool keeps = true;
      for (long k = 0; k < count; ++k) keeps = keeps && sign_of(nominal.det_a_norm(k)) == loop.sign;
      if (i == 0 || keeps) {
        result.plan = std::move(nominal);
        result.nominal = o.phi;
        result.found = true;
        return result;
      }
      if (!fallback.found) fallback.plan = std::move(nominal), fallback.nominal = o.phi, fallback.found = true;
      continue;
    }
    PartProgress part(progress, i, parts);
    RRR3Plan closed = plan_path(robot, points, count, o, progress ? &part : nullptr);
    if (closed.feasible && closed.sign == loop.sign) {
      result.plan = std::move(closed);
      result.nominal = o.phi;
      result.found = true;
      return result;
    }
  }
  if (fallback.found) return fallback;
  result.reason = started ? "plan" : "start";
  return result;
}

}  // namespace robokin
