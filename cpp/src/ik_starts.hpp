// Start configurations for the restarts of numerical IK: the closed-form solutions of a pose target
// when the chain's geometry has a closed form (closed_solve.hpp), and configurations spread over a
// chain's joint space with their tool poses, so that a solve whose first attempt fails restarts from
// an answer, then from those whose tool is nearest the target (a start near an answer converges
// where a random one may wander). Built once per chain (Chain::ik_starts), read-only afterwards:
// safe to share between threads.
#pragma once

#include "robokin/chain.hpp"
#include "robokin/closed_solve.hpp"
#include "robokin/limits.hpp"
#include "robokin/task.hpp"

#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <vector>

namespace robokin {

// A configuration drawn uniformly within the chain's limits; a joint without a finite limit on a
// side spans 2 pi (revolute) or 2 m (prismatic) from its other limit, or is centred on 0.
void random_configuration(const Chain& chain, std::mt19937_64& rng, double* q);

class IkStarts {
 public:
  // How many stored configurations: the search over them costs a few iterations of a solve, paid
  // only when the first attempt fails.
  static constexpr int kCount = 1024;

  // Reads the chain's closed form (closed_family: cheap); the stored configurations are drawn at
  // their first use. Every call that takes a `chain` takes one with the kinematics of this one.
  explicit IkStarts(const Chain& chain);
  ~IkStarts();

  // Whether pose targets get closed-form starts: the chain's geometry has a closed form.
  bool closed_form() const { return arm_.has_value(); }

  // Writes to out (room for ClosedFormSolutions::kMaxSolutions rows of n) the closed-form solutions
  // of a pose target that lie within the limits, nearest to q_ref (joint distance) first, and
  // returns how many: none for other tasks or a chain without a closed form.
  int closed(const Chain& chain, const Target& target, const double* q_ref, double* out) const;

  // Writes the indices of the `count` (<= kCount) stored starts nearest the target, nearest first,
  // in the target's task: the squared position distance (the task's rows) plus, for a pose, the
  // squared rotation angle, and for xyphi the squared planar angle, each weighted by the square of
  // half the farthest tool position among the starts (a turn of 2 rad counts like a move across
  // the arm's reach).
  void nearest(const Chain& chain, const Target& target, int count, int* out) const;
  // Stored start k: kCount configurations drawn by random_configuration from a fixed seed, the
  // same for every chain of the same kinematics (results do not depend on which copy solves).
  const double* q(const Chain& chain, int k) const;

 private:
  struct Stored;
  const Stored& stored(const Chain& chain) const;  // built at the first call (thread-safe)

  std::optional<ClosedArm> arm_;  // the chain's closed form, if its geometry has one
  JointLimits limits_;
  int n_;
  mutable std::once_flag stored_once_;
  mutable std::unique_ptr<const Stored> stored_;
};

}  // namespace robokin
