// One binding function per concept; module.cpp calls them all.
#pragma once

#include <pybind11/pybind11.h>

namespace robokin::bind {
void bind_chain(pybind11::module_& m);
void bind_reach(pybind11::module_& m);
void bind_rpr(pybind11::module_& m);
void bind_rrr3(pybind11::module_& m);
void bind_ik_closed(pybind11::module_& m);
void bind_ik(pybind11::module_& m);
void bind_urdf(pybind11::module_& m);  // after bind_chain: adds Chain.from_urdf
}  // namespace robokin::bind
