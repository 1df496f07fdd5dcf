// Flat panels: faces whose curvature display should stay flat (see metrics.hpp, "Flat panels shown flat").
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "edge_key.hpp"
#include "pushpull/deform/metrics.hpp"

namespace pushpull::deform {

std::vector<bool> flat_panel_faces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double crease_angle) {
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("flat_panel_faces: V and F must have 3 columns");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())) {
    throw std::invalid_argument("flat_panel_faces: a face index is outside [0, " + std::to_string(V.rows()) +
                                ")");
  }
  const Eigen::Index nf = F.rows();
  Eigen::Matrix3Xd normal(3, nf);
  std::vector<bool> has_normal(static_cast<std::size_t>(nf), false);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    has_normal[static_cast<std::size_t>(f)] = length > 0.0 && std::isfinite(length);
    normal.col(f) =
        has_normal[static_cast<std::size_t>(f)] ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }
  // Edges (key, face) sorted by key: the faces around each edge are adjacent in the list.
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(static_cast<std::size_t>(3 * nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      if (a != b) edges.emplace_back(detail::edge_key(a, b), static_cast<int>(f));
    }
  }
  std::sort(edges.begin(), edges.end());
  // A face stops being a flat panel at its first edge with a smooth (neither coplanar nor crease) bend.
  std::vector<bool> flat(static_cast<std::size_t>(nf), true);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 2) {  // boundary (1) and non-manifold (> 2) edges never bend a panel
      const int f = edges[i].second, g = edges[i + 1].second;
      if (has_normal[static_cast<std::size_t>(f)] && has_normal[static_cast<std::size_t>(g)]) {
        const Eigen::Vector3d nf_ = normal.col(f), ng = normal.col(g);
        const double angle = std::atan2(nf_.cross(ng).norm(), nf_.dot(ng));
        if (angle > kCoplanarDihedral && angle < crease_angle) {
          flat[static_cast<std::size_t>(f)] = false;
          flat[static_cast<std::size_t>(g)] = false;
        }
      }
    }
    i = j;
  }
  return flat;
}

std::vector<std::int8_t> display_curvature_signs(const std::vector<std::int8_t>& vertex_signs,
                                                 const Eigen::MatrixXi& F,
                                                 const std::vector<bool>& flat_panel) {
  if (flat_panel.size() != static_cast<std::size_t>(F.rows()))
    throw std::invalid_argument("display_curvature_signs: flat_panel must have one entry per face");
  if (F.size() > 0 && (F.minCoeff() < 0 || static_cast<std::size_t>(F.maxCoeff()) >= vertex_signs.size())) {
    throw std::invalid_argument("display_curvature_signs: a face index is outside the vertex signs");
  }
  std::vector<bool> shown(vertex_signs.size(), false);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (flat_panel[static_cast<std::size_t>(f)]) continue;
    for (int c = 0; c < 3; ++c) shown[static_cast<std::size_t>(F(f, c))] = true;
  }
  std::vector<std::int8_t> out(vertex_signs.size(), 0);
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = shown[v] ? vertex_signs[v] : 0;
  return out;
}

}  // namespace pushpull::deform
