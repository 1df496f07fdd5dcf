// Welding: merges coincident render vertices of all primitives (across patches, primitives and
// instances) into one deformable surface, and describes that surface's topology.
//
// Units: model (world) frame, file units. Thread-safety: pure functions, reentrant.
#pragma once

#include "pushpull/assets/scene.hpp"

#include <pushpull/deform/mesh.hpp>

#include <cstddef>
#include <vector>

namespace pushpull::assets {

struct WeldOptions {
  // Vertices closer than relative_tolerance * (bounding-box diagonal) are merged, so the same model
  // welds the same way at any scale (ToyCar is 7 cm, the Cesium truck hundreds of units).
  double relative_tolerance = 1e-5;
  // When >= 0, an absolute tolerance in model units that replaces the relative one.
  double absolute_tolerance = -1.0;
};

// Topology of a triangle mesh (computed on deform::Mesh::F).
struct Topology {
  std::size_t components = 0;          // connected components of faces (isolated vertices ignored)
  std::size_t boundary_edges = 0;      // edges with exactly one incident face
  std::size_t boundary_loops = 0;      // connected chains of boundary edges
  std::size_t non_manifold_edges = 0;  // edges with three or more incident faces
  // Faces that are degenerate by deform::is_degenerate_triangle (repeated vertex or zero area): kept in
  // the mesh, no stiffness in the solver; `pushpull deform` reports the same count.
  std::size_t degenerate_triangles = 0;
};

struct WeldStats {
  double tolerance = 0.0;           // absolute, model units
  std::size_t render_vertices = 0;  // vertices used by triangles, summed over primitives
  std::size_t deform_vertices = 0;  // after merging
  std::size_t render_triangles = 0;
  std::size_t deform_triangles = 0;
  std::size_t collapsed_triangles = 0;  // render triangles the weld collapsed (two corners merged), dropped
  std::size_t pieces_before = 0;        // connected pieces before welding (CAD patches)
  Topology topology;                    // of the welded surface
};

// Welds all triangles of `primitives` (placed by their T_model_node) into `out` (V in the model
// frame) and fills each primitive's deform_vertex map. Deterministic: same input, same output.
// exact_positions: for a single primitive read from a mesh file (OFF/OBJ/PLY), the reader's double positions
// (#V by 3, the model frame): the weld compares and keeps those instead of the stored floats (a model in
// large coordinates, e.g. 5e6 m, would otherwise merge everything within float's 0.5 m there).
WeldStats weld_primitives(std::vector<Primitive>& primitives, const WeldOptions& options, deform::Mesh& out,
                          const Eigen::MatrixXd* exact_positions = nullptr);

// Components, boundary loops, non-manifold edges and degenerate faces of a triangle mesh. F is #F by 3.
Topology analyze_topology(const deform::Mesh& mesh);

}  // namespace pushpull::assets
