#include "mesh_graph.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace pushpull::deform::detail {

VertexGraph build_vertex_graph(int vertex_count, const Eigen::MatrixXi& F, const std::vector<int>& faces) {
  std::vector<std::pair<int, int>> directed;
  directed.reserve(faces.size() * 6);
  for (int f : faces) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (a == b || b == c || c == a) continue;
    directed.insert(directed.end(), {{a, b}, {b, a}, {b, c}, {c, b}, {c, a}, {a, c}});
  }
  std::sort(directed.begin(), directed.end());
  directed.erase(std::unique(directed.begin(), directed.end()), directed.end());
  VertexGraph graph;
  graph.start.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  graph.index.reserve(directed.size());
  for (const auto& [from, to] : directed) {
    ++graph.start[static_cast<std::size_t>(from) + 1];
    graph.index.push_back(to);
  }
  std::partial_sum(graph.start.begin(), graph.start.end(), graph.start.begin());
  return graph;
}

VertexGraph build_vertex_graph(int vertex_count, const Eigen::MatrixXi& F) {
  std::vector<int> faces(static_cast<std::size_t>(F.rows()));
  std::iota(faces.begin(), faces.end(), 0);
  return build_vertex_graph(vertex_count, F, faces);
}

}  // namespace pushpull::deform::detail
