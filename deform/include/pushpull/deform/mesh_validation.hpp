// pushpull::deform mesh validation: what the solver accepts, what it repairs and what it refuses.
//
// Refused (MeshValidationError, message names the vertex / face index):
//   - V not #V by 3 or F not #F by 3;
//   - a NaN or infinite vertex coordinate;
//   - a face index outside [0, #V).
// Tolerated and reported in ValidationReport (the solver never produces NaN because of them):
//   - faces repeating a vertex index, zero-area (collinear) faces: they get zero weights (skipped);
//   - nearly degenerate faces (slivers): the solver's weights come from mollified edge lengths, bounded and
//     positive semidefinite per triangle (see deformer.hpp);
//   - unreferenced vertices: they never join a grown region; in an explicit region they are pinned;
//   - several connected components: a component of the region with no handle or fixed vertex is pinned;
//   - non-manifold edges (more than two faces): tolerated, every face contributes its cotangents.
//
// Thread-safety: free functions without state.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform {

class MeshValidationError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct ValidationReport {
  std::vector<int> degenerate_faces;       // repeated vertex index or zero area: skipped by the weights
  std::vector<int> unreferenced_vertices;  // used by no face
  std::vector<int> non_manifold_edges;     // face indices of faces on an edge shared by > 2 faces
  int component_count = 0;            // connected components of the face graph (isolated vertices excluded)
  std::vector<std::string> warnings;  // one readable line per finding above (lists abbreviated)

  [[nodiscard]] bool clean() const { return warnings.empty(); }
};

// The one definition of a degenerate triangle, used by validation, the solver's region faces and
// `pushpull info`: a repeated vertex index, or twice its area <= kDegenerateAreaRatio * (longest edge)^2
// (a sliver whose height is below 1e-14 of its longest edge: no stiffness a solver can use).
// V: #V by 3; a, b, c: indices into V (not checked).
inline constexpr double kDegenerateAreaRatio = 1e-14;
[[nodiscard]] bool is_degenerate_triangle(const Eigen::MatrixXd& V, int a, int b, int c);

// Throws MeshValidationError for refused input; returns the report otherwise. O(#V + #F log #F).
[[nodiscard]] ValidationReport validate_mesh(const Mesh& mesh);

}  // namespace pushpull::deform
