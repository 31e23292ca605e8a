// robokin._testing's subproblem hooks (subproblems.cpp), called by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace robokin::bind {
void bind_subproblem_hooks(pybind11::module_& m);
}  // namespace robokin::bind
