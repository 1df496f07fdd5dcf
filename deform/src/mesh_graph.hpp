// Private: vertex adjacency of a triangle mesh in compressed rows (neighbours of v are
// index[start[v] .. start[v+1])), built from the faces' edges; faces repeating a vertex are ignored.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pushpull::deform::detail {

struct VertexGraph {
  std::vector<int> start;  // #V + 1
  std::vector<int> index;  // sorted, unique neighbours per vertex

  [[nodiscard]] int vertex_count() const { return static_cast<int>(start.size()) - 1; }
  [[nodiscard]] const int* begin(int v) const { return index.data() + start[static_cast<std::size_t>(v)]; }
  [[nodiscard]] const int* end(int v) const { return index.data() + start[static_cast<std::size_t>(v) + 1]; }
};

// F: #F by 3 indices into [0, vertex_count) (validated by the caller).
[[nodiscard]] VertexGraph build_vertex_graph(int vertex_count, const Eigen::MatrixXi& F);

// Same for the faces given by their rows in F only.
[[nodiscard]] VertexGraph build_vertex_graph(int vertex_count, const Eigen::MatrixXi& F,
                                             const std::vector<int>& faces);

}  // namespace pushpull::deform::detail
