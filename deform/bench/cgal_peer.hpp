// CGAL's Surface_mesh_deformation (SPOKES_AND_RIMS, its default Eigen SparseLU solver) on a problem given
// as plain arrays, so that no other translation unit needs CGAL's headers.
#pragma once

#include "pushpull/deform/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace pushpull::bench {

struct PeerRun {
  double preprocess_ms = 0.0;     // insert ROI/control vertices + preprocess() (matrix build + factorization)
  double per_iteration_ms = 0.0;  // mean over the iterations run
  double converge_ms = 0.0;       // preprocess + iterations until within the target error of the reference
  double error = 0.0;             // final largest vertex distance to the reference (model units)
  int iterations = 0;
  bool converged = false;
  Eigen::MatrixXd V;  // final positions, #V by 3
};

// Free vertices = all except `fixed`; control vertices = `handle`, translated by d. Iterates one step at a
// time (deform(1, 0)) and stops once the largest vertex distance to `reference` (#V by 3, the same energy
// solved tightly) is <= target_error (model units), the same accuracy as the run it is compared with, or
// after max_iterations. Only the preprocessing and the deform() calls are timed; the distance check is not.
[[nodiscard]] PeerRun run_cgal_spokes_and_rims(const deform::Mesh& mesh, const std::vector<int>& handle,
                                               const std::vector<int>& fixed, const Eigen::Vector3d& d,
                                               const Eigen::MatrixXd& reference, double target_error,
                                               int max_iterations);

}  // namespace pushpull::bench
