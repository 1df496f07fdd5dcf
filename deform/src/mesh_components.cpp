#include "pushpull/deform/mesh_components.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>

namespace pushpull::deform {

std::vector<int> face_components(const Mesh& mesh) {
  const int nv = static_cast<int>(mesh.V.rows());
  std::vector<int> parent(static_cast<std::size_t>(nv));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int c = 1; c < 3; ++c) {
      const int a = find(mesh.F(f, 0)), b = find(mesh.F(f, c));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  std::vector<int> label(static_cast<std::size_t>(nv), -1), id_of_root(static_cast<std::size_t>(nv), -1);
  int next = 0;
  for (int v = 0; v < nv; ++v) {
    const int root = find(v);
    if (id_of_root[static_cast<std::size_t>(root)] < 0) id_of_root[static_cast<std::size_t>(root)] = next++;
    label[static_cast<std::size_t>(v)] = id_of_root[static_cast<std::size_t>(root)];
  }
  return label;
}

}  // namespace pushpull::deform
