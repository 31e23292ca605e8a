// robokin.Chain is bound in parts, one file each; bind_chain (chain.cpp) makes the class and adds
// them in this order (a later part may rely on an earlier one's methods: none does today).
#pragma once

#include <pybind11/pybind11.h>

#include "robokin/chain.hpp"

namespace robokin::bind {

void def_chain_model(pybind11::class_<Chain>& cls);           // chain.cpp: builders, dof, limits, frames, fk, jacobian
void def_chain_names(pybind11::class_<Chain>& cls);           // chain_names.cpp: joint and link names, q_from, q_dict
void def_chain_from_urdf(pybind11::class_<Chain>& cls);       // urdf.cpp: Chain.from_urdf
void def_chain_manipulability(pybind11::class_<Chain>& cls);  // manipulability.cpp: manipulability, ellipsoid
void def_chain_value(pybind11::class_<Chain>& cls);           // chain_value.cpp: pickling, ==, hash, repr

}  // namespace robokin::bind
