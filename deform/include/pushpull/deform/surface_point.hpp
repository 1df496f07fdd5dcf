// pushpull::deform surface points and the handle that grows from one along the surface.
//
// In the headset the handle comes from a ray hit on one triangle; on the command line from a point near the
// surface. Both become a SurfacePoint (a triangle and a point on it), and the handle is every vertex whose
// distance *along the surface* from that point is at most a radius. Growing along the surface, never through
// space, keeps the handle on the hit point's own component: a Euclidean ball would also grab a dashboard
// behind the cab wall or half of a lamp lens lying on the body (separate welded components).
//
// Distance along the surface: shortest edge paths (multi-source Dijkstra over mesh edges) seeded at the hit
// triangle's three corners with their straight-line distance to the point. This is the same metric as
// build_roi's region growing, so a handle radius and a region radius mean the same thing. It overestimates
// the true geodesic distance by at most the detour of edge paths (a few percent on fair meshes) and never
// leaves the component of the hit triangle.
//
// Units: model units. Frame: model space. Thread-safety: free functions without state; a SurfaceGraph is
// immutable after construction (const queries from any thread).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <span>
#include <vector>

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/roi.hpp"

namespace pushpull::deform {

struct SurfacePoint {
  int face = -1;                                    // row of Mesh::F holding the point
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // model space, on that triangle
};

// The point of the surface closest to p: exact point-triangle distance over every non-degenerate face
// (O(#F); the headset uses a BVH ray hit instead). Throws std::invalid_argument when p is not finite or the
// mesh has no non-degenerate face.
[[nodiscard]] SurfacePoint closest_surface_point(const Mesh& mesh, const Eigen::Vector3d& p);

// Distance along the surface (see above) from `from` to every vertex, up to max_distance; vertices farther
// away or on other components get +infinity. Throws std::invalid_argument when from.face is out of range or
// max_distance is NaN or negative.
[[nodiscard]] std::vector<double> surface_distances(
    const Mesh& mesh, const SurfacePoint& from,
    double max_distance = std::numeric_limits<double>::infinity());

// Handle vertices: every vertex within `radius` of `from` along the surface, and always at least the hit
// triangle's corner nearest to the point (so a small radius still grabs something). Sorted ascending.
// Throws std::invalid_argument as surface_distances, or when radius is NaN or negative.
[[nodiscard]] std::vector<int> surface_handle(const Mesh& mesh, const SurfacePoint& from, double radius);

// The same queries for many points on one mesh (a hand aiming at it frame after frame): the mesh's connectivity
// (vertex neighbours, faces around each vertex) is built once, O(#F log #F); each query then costs its Dijkstra
// within the radius plus O(#V) to allocate the distances. Positions are given per query (#V by 3, the same
// vertex count), so one graph serves every shape of a mesh whose faces do not change.
class SurfaceGraph {
 public:
  explicit SurfaceGraph(const Mesh& mesh);
  // As surface_distances / surface_handle on Mesh{V, the faces given to the constructor}; also throws
  // std::invalid_argument when V has another vertex count.
  [[nodiscard]] std::vector<double> distances(const Eigen::MatrixXd& V, const SurfacePoint& from,
                                              double max_distance = std::numeric_limits<double>::infinity()) const;
  [[nodiscard]] std::vector<int> handle(const Eigen::MatrixXd& V, const SurfacePoint& from, double radius) const;

 private:
  Eigen::MatrixXi F_;
  int vertex_count_ = 0;
  std::vector<int> neighbour_start_, neighbours_;  // compressed rows: the neighbours of each vertex
  std::vector<int> face_start_, faces_;            // compressed rows: the faces around each vertex
};

}  // namespace pushpull::deform
