// Mesh validation: refuse what cannot be deformed, report what is repaired (see mesh_validation.hpp).
#include "pushpull/deform/mesh_validation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

namespace pushpull::deform {
namespace {

// "3 faces (12, 40, 77)" with at most a few indices listed.
std::string abbreviated_list(const std::vector<int>& items, const char* noun) {
  std::ostringstream out;
  out << items.size() << ' ' << noun << " (";
  const std::size_t shown = std::min<std::size_t>(items.size(), 8);
  for (std::size_t i = 0; i < shown; ++i) out << (i ? ", " : "") << items[i];
  if (shown < items.size()) out << ", ...";
  out << ')';
  return out.str();
}

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    parent[static_cast<std::size_t>(v)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    v = parent[static_cast<std::size_t>(v)];
  }
  return v;
}

}  // namespace

bool is_degenerate_triangle(const Eigen::MatrixXd& V, int a, int b, int c) {
  if (a == b || b == c || c == a) return true;
  const Eigen::Vector3d pa = V.row(a), pb = V.row(b), pc = V.row(c);
  const double longest2 =
      std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
  return !((pb - pa).cross(pc - pa).norm() > kDegenerateAreaRatio * longest2);
}

ValidationReport validate_mesh(const Mesh& mesh) {
  const auto& V = mesh.V;
  const auto& F = mesh.F;
  if (V.cols() != 3) {
    throw MeshValidationError("mesh: V must be #V by 3, got " + std::to_string(V.rows()) + " by " +
                              std::to_string(V.cols()));
  }
  if (F.cols() != 3 && F.rows() > 0) {
    throw MeshValidationError("mesh: F must be #F by 3 (triangles), got " + std::to_string(F.rows()) +
                              " by " + std::to_string(F.cols()));
  }
  const Eigen::Index nv = V.rows();
  for (Eigen::Index v = 0; v < nv; ++v) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(V(v, c))) {
        std::ostringstream msg;
        msg << "mesh: vertex " << v << " has a non-finite coordinate (" << V(v, 0) << ", " << V(v, 1) << ", "
            << V(v, 2) << ")";
        throw MeshValidationError(msg.str());
      }
    }
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (F(f, c) < 0 || F(f, c) >= nv) {
        throw MeshValidationError("mesh: face " + std::to_string(f) + " corner " + std::to_string(c) +
                                  " references vertex " + std::to_string(F(f, c)) + ", valid range is [0, " +
                                  std::to_string(nv) + ")");
      }
    }
  }

  ValidationReport report;
  std::vector<char> referenced(static_cast<std::size_t>(nv), 0);
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  // Undirected edges (min, max, face) to find non-manifold edges.
  std::vector<std::array<int, 3>> edges;
  edges.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    for (int k = 0; k < 3; ++k) referenced[static_cast<std::size_t>(F(f, k))] = 1;
    if (is_degenerate_triangle(V, a, b, c)) {
      report.degenerate_faces.push_back(static_cast<int>(f));
      if (a == b || b == c || c == a) continue;  // not a triangle: no edges, no connectivity
    }
    const std::array<int, 3> tri = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const int i = tri[static_cast<std::size_t>(k)], j = tri[static_cast<std::size_t>((k + 1) % 3)];
      edges.push_back({std::min(i, j), std::max(i, j), static_cast<int>(f)});
      const int ri = find_root(parent, i), rj = find_root(parent, j);
      if (ri != rj) parent[static_cast<std::size_t>(ri)] = rj;
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<int> non_manifold_edge_count;
  for (std::size_t s = 0; s < edges.size();) {
    std::size_t e = s;
    while (e < edges.size() && edges[e][0] == edges[s][0] && edges[e][1] == edges[s][1]) ++e;
    if (e - s > 2) {
      for (std::size_t k = s; k < e; ++k) report.non_manifold_edges.push_back(edges[k][2]);
    }
    s = e;
  }
  std::sort(report.non_manifold_edges.begin(), report.non_manifold_edges.end());
  report.non_manifold_edges.erase(
      std::unique(report.non_manifold_edges.begin(), report.non_manifold_edges.end()),
      report.non_manifold_edges.end());
  for (Eigen::Index v = 0; v < nv; ++v) {
    if (!referenced[static_cast<std::size_t>(v)]) {
      report.unreferenced_vertices.push_back(static_cast<int>(v));
    } else if (find_root(parent, static_cast<int>(v)) == v) {
      ++report.component_count;
    }
  }

  if (!report.degenerate_faces.empty()) {
    report.warnings.push_back("mesh: " + abbreviated_list(report.degenerate_faces, "degenerate faces") +
                              " (repeated vertex or zero area) get zero weights");
  }
  if (!report.unreferenced_vertices.empty()) {
    report.warnings.push_back(
        "mesh: " + abbreviated_list(report.unreferenced_vertices, "unreferenced vertices") +
        " are used by no face; they do not move");
  }
  if (!report.non_manifold_edges.empty()) {
    report.warnings.push_back("mesh: " + abbreviated_list(report.non_manifold_edges, "faces") +
                              " lie on non-manifold edges (more than two faces); tolerated");
  }
  if (report.component_count > 1) {
    report.warnings.push_back("mesh: " + std::to_string(report.component_count) +
                              " connected components; a region component without handle or fixed vertex is "
                              "pinned");
  }
  return report;
}

}  // namespace pushpull::deform
