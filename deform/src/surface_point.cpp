// Surface points, distances along the surface and the handle grown from a point (see surface_point.hpp).
#include "pushpull/deform/surface_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

#include "mesh_graph.hpp"
#include "pushpull/deform/triangle_bvh.hpp"

namespace pushpull::deform {
namespace {

bool degenerate(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !((b - a).cross(c - a).norm() > 1e-14 * longest2);
}

void check_face(const Eigen::MatrixXi& F, const SurfacePoint& from) {
  if (from.face < 0 || from.face >= F.rows()) {
    throw std::invalid_argument("surface point: face " + std::to_string(from.face) + " is out of range [0, " +
                                std::to_string(F.rows()) + ")");
  }
  if (!from.point.allFinite()) throw std::invalid_argument("surface point: the point is not finite");
}

}  // namespace

SurfacePoint closest_surface_point(const Mesh& mesh, const Eigen::Vector3d& p) {
  if (!p.allFinite()) throw std::invalid_argument("closest surface point: the query point is not finite");
  SurfacePoint best;
  double best_distance2 = std::numeric_limits<double>::infinity();
  bool any_triangle = false;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    if (degenerate(a, b, c)) continue;
    const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, c);
    const double distance2 = (q - p).squaredNorm();
    any_triangle = true;
    if (distance2 < best_distance2) {
      best_distance2 = distance2;
      best.face = static_cast<int>(f);
      best.point = q;
    }
  }
  // (Every squared distance overflowed: a point some 1e154 model units away. Its nearest triangle cannot be
  // told this way, and no caller means such a point.)
  if (best.face < 0 && any_triangle)
    throw std::invalid_argument(
        "closest surface point: the point is too far from the mesh (1e154 or more away)");
  if (best.face < 0) {
    throw std::invalid_argument("closest surface point: the mesh has no non-degenerate triangle");
  }
  return best;
}

SurfaceGraph::SurfaceGraph(const Mesh& mesh) : F_(mesh.F), vertex_count_(static_cast<int>(mesh.V.rows())) {
  detail::VertexGraph graph = detail::build_vertex_graph(vertex_count_, mesh.F);
  neighbour_start_ = std::move(graph.start);
  neighbours_ = std::move(graph.index);
  // Faces around each vertex, in compressed rows.
  face_start_.assign(static_cast<std::size_t>(vertex_count_) + 1, 0);
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++face_start_[static_cast<std::size_t>(F_(f, c)) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(vertex_count_); ++v) face_start_[v + 1] += face_start_[v];
  faces_.resize(static_cast<std::size_t>(face_start_.back()));
  std::vector<int> fill(face_start_.begin(), face_start_.end() - 1);
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    for (int c = 0; c < 3; ++c) faces_[static_cast<std::size_t>(fill[static_cast<std::size_t>(F_(f, c))]++)] = int(f);
}

std::vector<double> SurfaceGraph::distances(const Eigen::MatrixXd& V, const SurfacePoint& from,
                                            double max_distance) const {
  if (V.rows() != vertex_count_)
    throw std::invalid_argument("surface distances: " + std::to_string(V.rows()) + " positions for a mesh of " +
                                std::to_string(vertex_count_) + " vertices");
  check_face(F_, from);
  if (std::isnan(max_distance) || max_distance < 0.0) {
    throw std::invalid_argument("surface distances: the maximum distance must be >= 0, got " +
                                std::to_string(max_distance));
  }
  std::vector<double> distance(static_cast<std::size_t>(vertex_count_), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  // Seeds: the corners of the hit triangle and of every triangle around it that also holds the point (a
  // point on an edge or a vertex lies in several), so the handle does not depend on which of them a ray
  // hit or a closest-point search happened to return.
  auto seed_face = [&](int f) {
    for (int c = 0; c < 3; ++c) {
      const int v = F_(f, c);
      const double dv = (V.row(v).transpose() - from.point).norm();
      if (dv <= max_distance && dv < distance[static_cast<std::size_t>(v)]) {
        distance[static_cast<std::size_t>(v)] = dv;
        queue.emplace(dv, v);
      }
    }
  };
  seed_face(from.face);
  for (int k = 0; k < 3; ++k) {  // the faces sharing a corner with the hit face
    const std::size_t corner = static_cast<std::size_t>(F_(from.face, k));
    for (int i = face_start_[corner]; i < face_start_[corner + 1]; ++i) {
      const int f = faces_[static_cast<std::size_t>(i)];
      if (f == from.face) continue;
      const Eigen::Vector3d a = V.row(F_(f, 0)), b = V.row(F_(f, 1)), c = V.row(F_(f, 2));
      if (degenerate(a, b, c)) continue;
      const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      if ((closest_point_on_triangle(from.point, a, b, c) - from.point).norm() <= 1e-9 * size) seed_face(f);
    }
  }
  while (!queue.empty()) {
    const auto [dv, v] = queue.top();
    queue.pop();
    if (dv > distance[static_cast<std::size_t>(v)]) continue;
    for (int i = neighbour_start_[static_cast<std::size_t>(v)]; i < neighbour_start_[static_cast<std::size_t>(v) + 1];
         ++i) {
      const int n = neighbours_[static_cast<std::size_t>(i)];
      const double dn = dv + (V.row(n) - V.row(v)).norm();
      if (dn <= max_distance && dn < distance[static_cast<std::size_t>(n)]) {
        distance[static_cast<std::size_t>(n)] = dn;
        queue.emplace(dn, n);
      }
    }
  }
  return distance;
}

std::vector<int> SurfaceGraph::handle(const Eigen::MatrixXd& V, const SurfacePoint& from, double radius) const {
  if (std::isnan(radius) || radius < 0.0) {
    throw std::invalid_argument("surface handle: the radius must be >= 0, got " + std::to_string(radius));
  }
  const std::vector<double> distance = distances(V, from, radius);
  std::vector<int> handle;
  for (std::size_t v = 0; v < distance.size(); ++v) {
    if (distance[v] <= radius) handle.push_back(static_cast<int>(v));
  }
  if (handle.empty()) {  // radius smaller than the distance to every corner: the nearest corner
    int nearest = F_(from.face, 0);
    for (int c = 1; c < 3; ++c) {
      const int v = F_(from.face, c);
      if ((V.row(v).transpose() - from.point).squaredNorm() < (V.row(nearest).transpose() - from.point).squaredNorm())
        nearest = v;
    }
    handle.push_back(nearest);
  }
  return handle;
}

std::vector<double> surface_distances(const Mesh& mesh, const SurfacePoint& from, double max_distance) {
  return SurfaceGraph(mesh).distances(mesh.V, from, max_distance);
}

std::vector<int> surface_handle(const Mesh& mesh, const SurfacePoint& from, double radius) {
  return SurfaceGraph(mesh).handle(mesh.V, from, radius);
}

}  // namespace pushpull::deform
