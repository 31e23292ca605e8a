// KDL's position IK solvers as the benchmarks' reference, called the way KDL users call them.
#include "kdl_ik_reference.hpp"

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include <stdexcept>

namespace robokin::testing {

struct KdlIkReference::Impl {
  KDL::Chain chain;
  std::unique_ptr<KDL::ChainFkSolverPos_recursive> fk;
  std::unique_ptr<KDL::ChainIkSolverVel_pinv> vel;
  std::unique_ptr<KDL::ChainIkSolverPos> pos;
  KDL::JntArray q_init, q_out;
};

KdlIkReference::KdlIkReference(const Chain& chain, const std::string& solver, int max_iter, double eps)
    : impl_(std::make_unique<Impl>()), dof_(chain.dof()) {
  Impl& s = *impl_;
  s.chain = chain.kdl();
  const unsigned n = s.chain.getNrOfJoints();
  s.q_init = KDL::JntArray(n);
  s.q_out = KDL::JntArray(n);
  if (solver == "lma") {  // KDL's default task-space weights (1, 1, 1, 0.01, 0.01, 0.01)
    s.pos = std::make_unique<KDL::ChainIkSolverPos_LMA>(s.chain, eps, max_iter);
  } else if (solver == "lma_unit") {  // unit weights: rotations count as much as positions
    s.pos = std::make_unique<KDL::ChainIkSolverPos_LMA>(s.chain, Eigen::Matrix<double, 6, 1>::Ones(), eps, max_iter);
  } else if (solver == "nr_jl") {
    KDL::JntArray lo(n), hi(n);
    lo.data = chain.lower();
    hi.data = chain.upper();
    s.fk = std::make_unique<KDL::ChainFkSolverPos_recursive>(s.chain);
    s.vel = std::make_unique<KDL::ChainIkSolverVel_pinv>(s.chain);
    s.pos = std::make_unique<KDL::ChainIkSolverPos_NR_JL>(s.chain, lo, hi, *s.fk, *s.vel, max_iter, eps);
  } else {
    throw std::invalid_argument("solver: expected 'lma', 'lma_unit' or 'nr_jl', got '" + solver + "'");
  }
}

KdlIkReference::~KdlIkReference() = default;

int KdlIkReference::solve(const Rigid& T, const Vector& q0, Vector& q) {
  Impl& s = *impl_;
  s.q_init.data = q0;
  const KDL::Frame goal(KDL::Rotation(T.R(0, 0), T.R(0, 1), T.R(0, 2), T.R(1, 0), T.R(1, 1), T.R(1, 2), T.R(2, 0),
                                      T.R(2, 1), T.R(2, 2)),
                        KDL::Vector(T.p(0), T.p(1), T.p(2)));
  const int code = s.pos->CartToJnt(s.q_init, goal, s.q_out);
  q = s.q_out.data;
  return code;
}

}  // namespace robokin::testing
