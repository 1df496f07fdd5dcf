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

void check_face(const Mesh& mesh, const SurfacePoint& from) {
  if (from.face < 0 || from.face >= mesh.F.rows()) {
    throw std::invalid_argument("surface point: face " + std::to_string(from.face) + " is out of range [0, " +
                                std::to_string(mesh.F.rows()) + ")");
  }
  if (!from.point.allFinite()) throw std::invalid_argument("surface point: the point is not finite");
}

}  // namespace

SurfacePoint closest_surface_point(const Mesh& mesh, const Eigen::Vector3d& p) {
  if (!p.allFinite()) throw std::invalid_argument("closest surface point: the query point is not finite");
  SurfacePoint best;
  double best_distance2 = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    if (degenerate(a, b, c)) continue;
    const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, c);
    const double distance2 = (q - p).squaredNorm();
    if (distance2 < best_distance2) {
      best_distance2 = distance2;
      best.face = static_cast<int>(f);
      best.point = q;
    }
  }
  if (best.face < 0) {
    throw std::invalid_argument("closest surface point: the mesh has no non-degenerate triangle");
  }
  return best;
}

std::vector<double> surface_distances(const Mesh& mesh, const SurfacePoint& from, double max_distance) {
  check_face(mesh, from);
  if (std::isnan(max_distance) || max_distance < 0.0) {
    throw std::invalid_argument("surface distances: the maximum distance must be >= 0, got " +
                                std::to_string(max_distance));
  }
  const int nv = static_cast<int>(mesh.V.rows());
  const detail::VertexGraph graph = detail::build_vertex_graph(nv, mesh.F);
  std::vector<double> distance(static_cast<std::size_t>(nv), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  // Seeds: the corners of the hit triangle and of every triangle around it that also holds the point (a
  // point on an edge or a vertex lies in several), so the handle does not depend on which of them a ray
  // hit or a closest-point search happened to return.
  auto seed_face = [&](int f) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(f, c);
      const double dv = (mesh.V.row(v).transpose() - from.point).norm();
      if (dv <= max_distance && dv < distance[static_cast<std::size_t>(v)]) {
        distance[static_cast<std::size_t>(v)] = dv;
        queue.emplace(dv, v);
      }
    }
  };
  seed_face(from.face);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (f == from.face) continue;
    bool shares_corner = false;
    for (int c = 0; c < 3 && !shares_corner; ++c)
      for (int k = 0; k < 3; ++k) shares_corner |= mesh.F(f, c) == mesh.F(from.face, k);
    if (!shares_corner) continue;
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    if (degenerate(a, b, c)) continue;
    const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if ((closest_point_on_triangle(from.point, a, b, c) - from.point).norm() <= 1e-9 * size)
      seed_face(static_cast<int>(f));
  }
  while (!queue.empty()) {
    const auto [dv, v] = queue.top();
    queue.pop();
    if (dv > distance[static_cast<std::size_t>(v)]) continue;
    for (const int* n = graph.begin(v); n != graph.end(v); ++n) {
      const double dn = dv + (mesh.V.row(*n) - mesh.V.row(v)).norm();
      if (dn <= max_distance && dn < distance[static_cast<std::size_t>(*n)]) {
        distance[static_cast<std::size_t>(*n)] = dn;
        queue.emplace(dn, *n);
      }
    }
  }
  return distance;
}

std::vector<int> surface_handle(const Mesh& mesh, const SurfacePoint& from, double radius) {
  if (std::isnan(radius) || radius < 0.0) {
    throw std::invalid_argument("surface handle: the radius must be >= 0, got " + std::to_string(radius));
  }
  const std::vector<double> distance = surface_distances(mesh, from, radius);
  std::vector<int> handle;
  for (std::size_t v = 0; v < distance.size(); ++v) {
    if (distance[v] <= radius) handle.push_back(static_cast<int>(v));
  }
  if (handle.empty()) {  // radius smaller than the distance to every corner: the nearest corner
    int nearest = mesh.F(from.face, 0);
    for (int c = 1; c < 3; ++c) {
      const int v = mesh.F(from.face, c);
      if ((mesh.V.row(v).transpose() - from.point).squaredNorm() <
          (mesh.V.row(nearest).transpose() - from.point).squaredNorm())
        nearest = v;
    }
    handle.push_back(nearest);
  }
  return handle;
}

}  // namespace pushpull::deform
