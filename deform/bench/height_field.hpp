// The benchmark problem: an n x n jittered height field over [0, 1]^2 (n^2 vertices), a disk of vertices at
// the centre as handle, the outer ring of the grid fixed, the whole sheet as region of interest.
#pragma once

#include "pushpull/deform/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace pushpull::bench {

struct HeightFieldProblem {
  deform::Mesh mesh;
  std::vector<int> handle;  // vertices within handle_radius of the centre (in x, y)
  std::vector<int> fixed;   // the grid's outer ring
  Eigen::Vector3d d;        // push/pull displacement of the handle
};

// Deterministic: the jitter comes from a fixed-seed generator.
[[nodiscard]] HeightFieldProblem make_height_field(int n, double handle_radius = 0.08,
                                                   const Eigen::Vector3d& d = Eigen::Vector3d(0.0, 0.0, 0.1));

}  // namespace pushpull::bench
