// Manipulability measures and ellipsoids from the singular values of the geometric Jacobian
// (Eigen's JacobiSVD of the task's rows, at the tool point, in the base frame).
#pragma once

#include "robokin/chain.hpp"
#include "robokin/progress.hpp"
#include "robokin/task.hpp"

#include <string>

namespace robokin {

// yoshikawa: the product of the singular values (sqrt(det(J J^T)) when the task has at most dof
// rows); condition: sigma_min / sigma_max, the inverse condition number, in [0, 1] (1 isotropic,
// 0 singular; 0 for a zero Jacobian); min_singular: sigma_min. All three are 0 at a singularity.
enum class Measure { Yoshikawa, Condition, MinSingular };

Measure parse_measure(const std::string& name);  // "yoshikawa" | "condition" | "min_singular"

// The measure at q (dof values).
double manipulability(const Chain& chain, const double* q, Task task, Measure measure);
// One value per configuration of q (count x dof, row-major), in parallel. The caller releases the GIL.
void manipulability_batch(const Chain& chain, const double* q, long count, Task task, Measure measure, double* out,
                          Progress* progress = nullptr);

// The velocity ellipsoid of the translational (rotation = false: rows v) or rotational (rows w)
// part of the Jacobian at q: the principal axes (unit columns, base frame) and their lengths (the
// singular values, in decreasing order).
void ellipsoid(const Chain& chain, const double* q, bool rotation, Eigen::Matrix3d& axes, Eigen::Vector3d& lengths);

}  // namespace robokin
