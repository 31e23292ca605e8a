// 3-RRR constant-orientation workspace on a grid, and the seed's design study (section 3).
#pragma once

#include "robokin/rrr3.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace robokin {

enum class WorkspaceCell : std::uint8_t { Unreachable = 0, Regular = 1, Parallel = 2, Serial = 3 };

struct RRR3Workspace {
  long n = 0;                   // n x n cells, row j at y = y0 + (j + 1/2) h, column i at x = x0 + (i + 1/2) h
  double x0 = 0, y0 = 0, h = 0; // lower-left corner and cell side (m)
  std::vector<std::uint8_t> cells;  // Cell codes, row-major (row = y)
  double reachable_area = 0;    // every reachable cell (m^2)
  double regular_area = 0;      // reachable cells that are not singular
  double region_area = 0;       // the largest 4-connected set of regular cells: what the robot can
                                // sweep at this orientation without crossing a singularity

  Eigen::VectorXd x() const;      // cell centres along x (n)
  Eigen::VectorXd y() const;      // cell centres along y (n)
  std::array<double, 4> extent() const;  // (x_min, x_max, y_min, y_max) of the grid
};

// What a workspace map is made of.
struct RRR3WorkspaceOptions {
  double phi = 0;             // the platform's orientation (rad)
  Mode mode = kDefaultMode;     // the working mode
  long n = 200;               // n x n cells, n in [2, 5000]
  double tol = kSingularTol;  // singular cell: |det B| / l1^3 or |det A| / R_e below tol

  // Every option, its Python keyword and its doc, in order (the bindings bind exactly these).
  template <class Visit>
  static void fields(Visit&& field) {
    field("phi", &RRR3WorkspaceOptions::phi, "The platform's orientation (rad).");
    field("mode", &RRR3WorkspaceOptions::mode, "The working mode.");
    field("n", &RRR3WorkspaceOptions::n, "n x n cells, n in [2, 5000].");
    field("tol", &RRR3WorkspaceOptions::tol, "Singular cell: |det B| / l1^3 or |det A| / R_e below tol.");
  }

  // Throws std::invalid_argument("name: ...") for an option out of range.
  void validate() const;
};

// The workspace at orientation phi in one working mode. The grid is the square around the
// intersection of the three disks the platform centre can reach (leg i: centre O_i - R(phi) b_i,
// radius l1 + l2). A reachable cell is "serial" when |det B| / l1^3 < tol and "parallel" when
// |det A| / R_e < tol or det A has the opposite sign in a 4-neighbour (a singular curve crosses
// between the two cell centres, so the curve shows without gaps however fine it is). Uses every core.
// Validates the options (std::invalid_argument).
RRR3Workspace workspace(const RRR3& robot, const RRR3WorkspaceOptions& options, Progress* progress = nullptr);

// The largest singularity-free region area of each robot of a design study, on the maps of options.
std::vector<double> region_areas(const std::vector<RRR3>& robots, const RRR3WorkspaceOptions& options,
                                 Progress* progress = nullptr);

}  // namespace robokin
