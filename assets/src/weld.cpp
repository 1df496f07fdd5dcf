#include "pushpull/assets/weld.hpp"

#include <pushpull/deform/mesh_validation.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace pushpull::assets {

namespace {

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int64_t v : c) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

std::int64_t cell_coordinate(double x, double cell) {
  const double c = std::floor(x / cell);
  return static_cast<std::int64_t>(std::clamp(c, -4.0e18, 4.0e18));
}

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

Topology analyze_topology(const deform::Mesh& mesh) {
  Topology topology;
  const auto n = static_cast<std::size_t>(mesh.V.rows());
  UnionFind vertices(n);
  std::unordered_map<std::uint64_t, int> edge_faces;
  edge_faces.reserve(static_cast<std::size_t>(mesh.F.rows()) * 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      ++edge_faces[edge_key(a, b)];
      vertices.unite(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
    }
  std::vector<bool> used(n, false);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) used[static_cast<std::size_t>(mesh.F(f, c))] = true;
  for (std::size_t v = 0; v < n; ++v)
    if (used[v] && vertices.find(v) == v) ++topology.components;

  // Boundary loops: connected groups of boundary edges (a vertex where two loops touch joins them).
  UnionFind boundary(n);
  std::vector<bool> on_boundary(n, false);
  for (const auto& [key, count] : edge_faces) {
    if (count >= 3) ++topology.non_manifold_edges;
    if (count != 1) continue;
    ++topology.boundary_edges;
    const auto a = static_cast<std::size_t>(key >> 32), b = static_cast<std::size_t>(key & 0xFFFFFFFFu);
    boundary.unite(a, b);
    on_boundary[a] = on_boundary[b] = true;
  }
  for (std::size_t v = 0; v < n; ++v)
    if (on_boundary[v] && boundary.find(v) == v) ++topology.boundary_loops;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (deform::is_degenerate_triangle(mesh.V, mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)))
      ++topology.degenerate_triangles;
  return topology;
}

WeldStats weld_primitives(std::vector<Primitive>& primitives, const WeldOptions& options, deform::Mesh& out,
                          const Eigen::MatrixXd* exact_positions) {
  WeldStats stats;
  if (exact_positions != nullptr &&
      (primitives.size() != 1 || exact_positions->rows() != primitives.front().positions.rows()))
    exact_positions = nullptr;
  // A render vertex's model-frame position: the reader's doubles where given, else the stored floats.
  std::vector<Eigen::Affine3d> T_model_node;
  T_model_node.reserve(primitives.size());
  for (const Primitive& primitive : primitives) T_model_node.emplace_back(primitive.T_model_node);
  auto position = [&](std::size_t p, Eigen::Index v) -> Eigen::Vector3d {
    if (exact_positions != nullptr) return exact_positions->row(v).transpose();
    return T_model_node[p] * primitives[p].positions.row(v).transpose().cast<double>();
  };
  // Model-frame positions of every render vertex used by a triangle, and the bounding box.
  std::vector<std::vector<bool>> used(primitives.size());
  Eigen::AlignedBox3d box;
  std::size_t render_total = 0;
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    Primitive& primitive = primitives[p];
    used[p].assign(static_cast<std::size_t>(primitive.positions.rows()), false);
    for (std::uint32_t i : primitive.indices) used[p][i] = true;
    for (Eigen::Index v = 0; v < primitive.positions.rows(); ++v)
      if (used[p][static_cast<std::size_t>(v)]) {
        box.extend(position(p, v));
        ++render_total;
      }
    stats.render_triangles += primitive.indices.size() / 3;
  }
  stats.render_vertices = render_total;
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  stats.tolerance =
      options.absolute_tolerance >= 0.0 ? options.absolute_tolerance : options.relative_tolerance * diagonal;
  const double tolerance = stats.tolerance;
  // Grid cells of the tolerance's size keep each cell's representatives few (they are pairwise
  // farther apart than the tolerance); an exact weld (tolerance 0) still needs small cells.
  const double cell = tolerance > 0.0 ? tolerance : (diagonal > 0.0 ? 1e-6 * diagonal : 1.0);

  // Greedy merge on a uniform grid: a vertex joins the first earlier representative within the
  // tolerance (searching the 27 neighbouring cells), otherwise it becomes a representative.
  std::vector<Eigen::Vector3d> representatives;
  representatives.reserve(render_total);
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<int>, CellHash> grid;
  grid.reserve(render_total);
  std::vector<std::size_t> render_offset(primitives.size() + 1, 0);
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    Primitive& primitive = primitives[p];
    render_offset[p + 1] = render_offset[p] + static_cast<std::size_t>(primitive.positions.rows());
    primitive.deform_vertex.assign(static_cast<std::size_t>(primitive.positions.rows()), -1);
    for (Eigen::Index v = 0; v < primitive.positions.rows(); ++v) {
      if (!used[p][static_cast<std::size_t>(v)]) continue;
      const Eigen::Vector3d x = position(p, v);
      const std::array<std::int64_t, 3> c{cell_coordinate(x.x(), cell), cell_coordinate(x.y(), cell),
                                          cell_coordinate(x.z(), cell)};
      int match = -1;
      double best = tolerance * tolerance;
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == grid.end()) continue;
            for (int r : it->second) {
              const double d = (representatives[static_cast<std::size_t>(r)] - x).squaredNorm();
              if (d <= best && (match < 0 || d < best || r < match)) {
                best = d;
                match = r;
              }
            }
          }
      if (match < 0) {
        match = static_cast<int>(representatives.size());
        representatives.push_back(x);
        grid[c].push_back(match);
      }
      primitive.deform_vertex[static_cast<std::size_t>(v)] = match;
    }
  }

  out.V.resize(static_cast<Eigen::Index>(representatives.size()), 3);
  for (std::size_t r = 0; r < representatives.size(); ++r)
    out.V.row(static_cast<Eigen::Index>(r)) = representatives[r].transpose();
  stats.deform_vertices = representatives.size();

  // Faces through the map; triangles that collapse under the weld are dropped. Pieces before the
  // weld: components of the unwelded render triangles.
  UnionFind pieces(render_offset.back());
  std::vector<std::array<int, 3>> faces;
  faces.reserve(stats.render_triangles);
  for (std::size_t p = 0; p < primitives.size(); ++p) {
    const Primitive& primitive = primitives[p];
    // A mirroring node transform flips the winding (glTF 2.0, 3.7.4); the deform mesh keeps
    // counter-clockwise-from-outside triangles, so swap two corners for such instances.
    const bool mirrored = primitive.T_model_node.topLeftCorner<3, 3>().determinant() < 0.0;
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
      const std::uint32_t* i = &primitive.indices[t];
      pieces.unite(render_offset[p] + i[0], render_offset[p] + i[1]);
      pieces.unite(render_offset[p] + i[0], render_offset[p] + i[2]);
      std::array<int, 3> f{primitive.deform_vertex[i[0]], primitive.deform_vertex[i[1]],
                           primitive.deform_vertex[i[2]]};
      if (mirrored) std::swap(f[1], f[2]);
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
        ++stats.collapsed_triangles;
        continue;
      }
      faces.push_back(f);
    }
  }
  for (std::size_t p = 0; p < primitives.size(); ++p)
    for (std::size_t v = 0; v < used[p].size(); ++v)
      if (used[p][v] && pieces.find(render_offset[p] + v) == render_offset[p] + v) ++stats.pieces_before;

  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    out.F.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  stats.deform_triangles = faces.size();
  stats.topology = analyze_topology(out);
  return stats;
}

}  // namespace pushpull::assets
