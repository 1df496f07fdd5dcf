// The benchmark problem: an n x n jittered height field over [0, 1]^2 (n^2 vertices), a disk of vertices at
// the centre as handle, the outer ring of the grid fixed, the whole sheet as region of interest.
#pragma once

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/method.hpp"
#include "pushpull/deform/roi.hpp"

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

// The benchmarks' reference: `method`'s energy for the pull d solved from rest until the solver's estimate
// is below 1e-9 |d| (at most 50000 iterations). #V by 3 positions.
[[nodiscard]] Eigen::MatrixXd reference_solution(const deform::Mesh& mesh,
                                                 const deform::RegionOfInterest& roi,
                                                 const Eigen::Vector3d& d, deform::Method method);

}  // namespace pushpull::bench
