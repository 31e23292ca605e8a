// Cuspidality of a 3R positioning arm: its aspects (regions of constant sign of det J), the cusp
// points of its singular curves and, for a cuspidal arm, a posture change that meets no singularity.
#pragma once

#include "robokin/chain.hpp"

#include <Eigen/Core>

#include <cstdint>

namespace robokin {

// The options of cuspidal.
struct CuspidalOptions {
  int resolution = 256;

  template <class Visit>
  static void fields(Visit&& field) {
    field("resolution", &CuspidalOptions::resolution,
          "Grid size N on the (q2, q3) torus, 16 to 4096: the singular curves are traced cell by cell and "
          "each cusp refined by bisection along the curve.");
  }
  // Throws std::invalid_argument("resolution: ...") outside [16, 4096].
  void validate() const;
};

struct Cuspidality {
  using Cusps = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;
  using Path = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using Signs = Eigen::Matrix<std::int8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Labels = Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  bool cuspidal = false;  // the arm can change posture without meeting a singularity
  Cusps cusps;            // (k, 4): q2, q3 on the singular curve, rho, z of its workspace point
  int aspects = 0;        // connected regions of one sign of det J on the (q2, q3) torus
  Eigen::VectorXd grid;   // (N,): the grid's angles, q = -pi + (i + 0.37) 2 pi / N, for q2 and q3
  Signs sign;             // (N, N): sign(det J), row = q2
  Labels label;           // (N, N): the aspect of each cell, -1 where det J = 0
  Eigen::VectorXd point;  // a tool point with two solutions in one aspect; empty when none is found
  Path path;              // joints from one of them to the other, det J of one sign all along; or empty

  template <class F>
  static void fields(F&& f) {
    f("cuspidal", &Cuspidality::cuspidal, "The arm can change posture without meeting a singularity.");
    f("cusps", &Cuspidality::cusps,
      "(k, 4) one row per cusp point, q2 and q3 on the singular curve, then rho and z of its workspace point "
      "(distance from axis 1 and height along it, in the base frame).");
    f("aspects", &Cuspidality::aspects, "Number of aspects (connected regions of one sign of det J on the (q2, q3) torus).");
    f("grid", &Cuspidality::grid, "(N,) the joint angles of the grid's rows (q2) and columns (q3).");
    f("sign", &Cuspidality::sign, "(N, N) sign of det J on the grid (int8), row = q2.");
    f("label", &Cuspidality::label, "(N, N) the aspect of each grid cell (int32), -1 on a singularity.");
  }
};

// Traces det D = 0 (D: the 2 x 2 Jacobian of (q2, q3) -> (rho, z)) on an N x N (options.resolution)
// grid of the torus, and finds where the image of the curve's tangent, D tau, reverses (a cusp of
// the singular curve in the workspace, where three solutions coincide); each is refined by
// bisection along the curve. The aspects are the grid's 4-connected regions of one sign of det J.
// For a cuspidal arm, points near each cusp are tried until two of a point's solutions lie in one
// aspect and a path of grid cells joins them whose det J keeps its sign (checked at 9 points of
// each step, its ends included): the posture change. Throws std::invalid_argument when the chain
// is not a 3R arm or the options are not valid.
Cuspidality cuspidal(const Chain& chain, const CuspidalOptions& options = {});

}  // namespace robokin
