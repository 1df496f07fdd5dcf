// Test meshes with slivers: a gently domed square sheet with needles and caps of a chosen aspect ratio
// embedded in an otherwise regular triangulation, for the weight and solver tests.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform::testing {

enum class Sliver { Cap, Needle };

struct SliverSheet {
  Mesh mesh;
  int grid_vertices = 0;           // vertices [0, grid_vertices) are the regular grid, row j * (n + 1) + i
  std::vector<int> sliver_vertex;  // the extra vertex of each sliver cell
};

// (n+1)^2 grid on [0,1]^2 with z = 0.1 sin(pi x) sin(pi y), cells split along alternating diagonals, except
// the listed cells (i, j) -> kind, which get a fifth vertex m and four triangles (a,b,m),(b,c,m),(c,d,m),
// (d,a,m) around it (a = (i,j), b = (i+1,j), c = (i+1,j+1), d = (i,j+1)):
//   Cap:    m lies `aspect` x |ab| off the middle of edge ab, towards the cell centre: triangle (a,b,m)
//           has an angle of ~180 degrees at m and height / longest edge = aspect.
//   Needle: m lies on the diagonal at `aspect` x |ac| from c: triangles (b,c,m) and (c,d,m) have a
//           short edge |cm| and an angle of ~aspect radians at b and d.
inline SliverSheet sliver_sheet(int n, const std::map<std::pair<int, int>, Sliver>& slivers, double aspect) {
  SliverSheet s;
  auto height = [](double x, double y) {
    return 0.1 * std::sin(std::numbers::pi * x) * std::sin(std::numbers::pi * y);
  };
  std::vector<Eigen::Vector3d> V;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
      V.emplace_back(x, y, height(x, y));
    }
  }
  s.grid_vertices = static_cast<int>(V.size());
  std::vector<Eigen::Vector3i> F;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, d = a + n + 1, c = d + 1;
      const auto it = slivers.find({i, j});
      if (it == slivers.end()) {
        if ((i + j) % 2 == 0) {
          F.emplace_back(a, b, c);
          F.emplace_back(a, c, d);
        } else {
          F.emplace_back(a, b, d);
          F.emplace_back(b, c, d);
        }
        continue;
      }
      Eigen::Vector3d m;
      if (it->second == Sliver::Cap) {
        const Eigen::Vector3d mid = 0.5 * (V[a] + V[b]);
        const Eigen::Vector3d centre = 0.25 * (V[a] + V[b] + V[c] + V[d]);
        // |centre - mid| is about |ab| / 2, so this puts m at aspect x |ab| from the edge.
        m = mid + 2.0 * aspect * (centre - mid);
      } else {
        m = V[c] + aspect * (V[a] - V[c]);
      }
      const int mi = static_cast<int>(V.size());
      V.push_back(m);
      s.sliver_vertex.push_back(mi);
      F.emplace_back(a, b, mi);
      F.emplace_back(b, c, mi);
      F.emplace_back(c, d, mi);
      F.emplace_back(d, a, mi);
    }
  }
  s.mesh.V.resize(static_cast<Eigen::Index>(V.size()), 3);
  for (std::size_t k = 0; k < V.size(); ++k) s.mesh.V.row(static_cast<Eigen::Index>(k)) = V[k].transpose();
  s.mesh.F.resize(static_cast<Eigen::Index>(F.size()), 3);
  for (std::size_t k = 0; k < F.size(); ++k) s.mesh.F.row(static_cast<Eigen::Index>(k)) = F[k].transpose();
  return s;
}

}  // namespace pushpull::deform::testing
