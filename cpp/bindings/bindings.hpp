// One binding function per concept; module.cpp calls them all.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <utility>

namespace robokin::bind {
void bind_errors(pybind11::module_& m);  // first: translators for the core's and KDL's exceptions
void bind_chain(pybind11::module_& m);  // the Chain class
void bind_reach(pybind11::module_& m);
void bind_rpr(pybind11::module_& m);
void bind_rrr3(pybind11::module_& m);
void bind_closed(pybind11::module_& m);  // robokin.closed: IKSolutions, the closed forms, ClosedSolver
void bind_ik(pybind11::module_& m);
void bind_urdf(pybind11::module_& m);  // the URDF parser for robokin._urdf, the URDF tree's classes
// The serial-arm toolkit: trajectories, velocity-level IK, pose helpers.
void bind_traj(pybind11::module_& m);
void bind_resolved_rate(pybind11::module_& m);
void bind_pose(pybind11::module_& m);
void bind_general_3r(pybind11::module_& m);  // general 3R arms
void bind_cuspidal(pybind11::module_& m);  // cuspidality of 3R arms
void bind_postures(pybind11::module_& m);  // track_postures' dynamic programme

// Text for people (repr, str, tables) is written in Python: robokin._printing.function(args...).
template <class... A>
std::string printed(const char* function, A&&... args) {
  const pybind11::object text = pybind11::module_::import("robokin._printing").attr(function)(std::forward<A>(args)...);
  return text.cast<std::string>();
}
}  // namespace robokin::bind
