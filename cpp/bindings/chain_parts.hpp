// robokin.Chain is bound in parts, one file each; bind_chain (chain.cpp) makes the class and adds
// them in this order (a later part may rely on an earlier one's methods: none does today).
#pragma once

#include <pybind11/pybind11.h>

#include "arrays.hpp"

#include "robokin/chain.hpp"

namespace robokin::bind {

void def_chain_model(pybind11::class_<Chain>& cls);           // chain.cpp: builders, dof, limits, frames
void def_chain_fast_calls(pybind11::class_<Chain>& cls);      // fast_calls.cpp: fk, jacobian, manipulability
void def_chain_names(pybind11::class_<Chain>& cls);           // chain_names.cpp: joint and link names, q_from, q_dict
void def_chain_from_urdf(pybind11::class_<Chain>& cls);       // urdf.cpp: Chain.from_urdf
void def_chain_manipulability(pybind11::class_<Chain>& cls);  // manipulability.cpp: ellipsoid
void def_chain_value(pybind11::class_<Chain>& cls);           // chain_value.cpp: pickling, ==, hash, repr

// The functions of the fast methods (fast_calls.cpp binds them).
pybind11::array chain_fk(const Chain& c, ArrayLike q, FkPart part, OutArray out);                 // chain.cpp
pybind11::array chain_jacobian(const Chain& c, ArrayLike q, TaskName task, OutArray out);         // chain.cpp
pybind11::object chain_manipulability(const Chain& c, ArrayLike q, MeasureName measure, TaskName task);  // manipulability.cpp

}  // namespace robokin::bind
