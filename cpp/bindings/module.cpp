#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "robokin's C++ core (Eigen + Orocos KDL). Use it through the robokin package.";
  robokin::bind::bind_errors(m);
  robokin::bind::bind_chain(m);
  robokin::bind::bind_reach(m);
  robokin::bind::bind_rpr(m);
  robokin::bind::bind_rrr3(m);
  robokin::bind::bind_closed(m);
  robokin::bind::bind_ik(m);
  robokin::bind::bind_urdf(m);
  // Trajectories, velocity-level IK, pose helpers.
  robokin::bind::bind_traj(m);
  robokin::bind::bind_resolved_rate(m);
  robokin::bind::bind_pose(m);
  robokin::bind::bind_general_3r(m);
  robokin::bind::bind_cuspidal(m);
  robokin::bind::bind_postures(m);
}
