// KDL's position IK solvers as the benchmarks' reference (robokin._testing.KdlIk), not part of the
// library: ChainIkSolverPos_LMA ("lma", KDL's default weights; "lma_unit", unit weights) and
// ChainIkSolverPos_NR_JL ("nr_jl", with ChainIkSolverVel_pinv and the chain's limits), built once
// and called as KDL users call them.
#pragma once

#include "robokin/chain.hpp"

#include <memory>
#include <string>

namespace robokin::testing {

class KdlIkReference {
 public:
  KdlIkReference(const Chain& chain, const std::string& solver, int max_iter, double eps);
  ~KdlIkReference();
  // Returns KDL's error code (>= 0 on success as KDL sees it); q holds KDL's answer.
  int solve(const Rigid& target, const Vector& q0, Vector& q);
  int dof() const { return dof_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int dof_ = 0;
};

}  // namespace robokin::testing
