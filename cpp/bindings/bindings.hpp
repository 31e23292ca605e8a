// One binding function per concept; module.cpp calls them all.
#pragma once

#include <pybind11/pybind11.h>

namespace robokin::bind {
void bind_errors(pybind11::module_& m);  // first: translators for the core's and KDL's exceptions
void bind_chain(pybind11::module_& m);
void bind_reach(pybind11::module_& m);
void bind_rpr(pybind11::module_& m);
void bind_rrr3(pybind11::module_& m);
void bind_ik_closed(pybind11::module_& m);
void bind_ik(pybind11::module_& m);
void bind_urdf(pybind11::module_& m);  // after bind_chain: adds Chain.from_urdf
// The serial-arm toolkit: trajectories, manipulability, velocity-level IK, pose helpers.
void bind_traj(pybind11::module_& m);
void bind_manipulability(pybind11::module_& m);  // after bind_chain: adds Chain methods
void bind_resolved_rate(pybind11::module_& m);
void bind_pose(pybind11::module_& m);
void bind_ik_3r(pybind11::module_& m);  // general 3R arms, cuspidality
void bind_output_pool(pybind11::module_& m);  // release_output_memory
void bind_chain_pickle(pybind11::module_& m);  // after bind_chain: Chain pickling, ==, hash, repr
void bind_chain_names(pybind11::module_& m);   // after bind_chain: joint_names, link_names, q_from, q_dict
void bind_postures(pybind11::module_& m);  // track_postures' dynamic programme
}  // namespace robokin::bind
