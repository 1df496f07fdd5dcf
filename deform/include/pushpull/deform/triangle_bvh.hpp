// pushpull::deform::TriangleBvh: a bounding-volume hierarchy over a subset of a mesh's triangles, for the
// closest surface point to a query point and the first triangle a ray hits.
//
// Binary tree of axis-aligned boxes built by median split along the longest axis of the box centroids
// (O(F log F)); leaves hold up to 4 triangles. Queries descend nearest box first and prune by distance, so a
// query costs O(log F) on fair meshes. refit() recomputes the boxes for moved vertices without rebuilding the
// tree (previews of a deformation: topology unchanged, positions moved a little).
//
// Units and frame: those of the positions given (model units, model space).
// Ownership: copies the face list; positions are passed to each call (#V by 3, the same indexing as the
// faces), so one tree serves the rest and the deformed shape alike after refit().
// Thread-safety: const queries may run concurrently; build/refit need exclusive access.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

namespace pushpull::deform {

class TriangleBvh {
 public:
  struct Hit {
    int face = -1;                                    // row of F (an index into the faces given to build)
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the closest point / the ray's hit point
    double distance = std::numeric_limits<double>::infinity();  // to the query point / along the ray
  };

  TriangleBvh() = default;
  // V: #V by 3 positions; F: #F by 3 vertex indices; faces: the rows of F to include (empty = all rows).
  // Degenerate triangles (zero area) are left out.
  TriangleBvh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& faces = {});

  // Same faces, moved positions.
  void refit(const Eigen::MatrixXd& V);

  [[nodiscard]] bool empty() const { return nodes_.empty(); }
  // The closest point of the included triangles to p within max_distance (none beyond it or when empty).
  [[nodiscard]] std::optional<Hit> closest_point(
      const Eigen::MatrixXd& V, const Eigen::Vector3d& p,
      double max_distance = std::numeric_limits<double>::infinity()) const;
  // The first included triangle hit by origin + t * direction, 0 <= t <= max_t (direction need not be unit;
  // distance is then t * |direction|). Both sides of a triangle count.
  [[nodiscard]] std::optional<Hit> ray_hit(const Eigen::MatrixXd& V, const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& direction,
                                           double max_t = std::numeric_limits<double>::infinity()) const;

 private:
  struct Node {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
    int first = 0,
        count = 0;  // leaf: faces_[first, first + count); inner: count = 0, children first, first+1
  };
  void build(int node, int begin, int end, const Eigen::MatrixXd& V);
  void fit(int node, const Eigen::MatrixXd& V);

  Eigen::MatrixXi F_;
  std::vector<int> faces_;  // rows of F_, reordered so that each leaf's faces are contiguous
  std::vector<Node> nodes_;
};

// Closest point to p on triangle (a, b, c).
[[nodiscard]] Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace pushpull::deform
