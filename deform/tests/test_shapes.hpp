// Meshes of known shapes for tests: height-field grids, an icosphere, an open cylinder.
#pragma once

#include "pushpull/deform/mesh.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace pushpull::deform::testing {

// Both meshes as one (b's vertices after a's): separate components, e.g. a part lying on a panel.
inline Mesh append(const Mesh& a, const Mesh& b) {
  Mesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

// (nx+1) x (ny+1) vertices on [x0,x1] x [y0,y1], z = height(x, y); vertex (i, j) is row j * (nx+1) + i.
// Each cell is split along alternating diagonals so the mesh has no preferred direction.
inline Mesh grid(
    int nx, int ny, double x0, double x1, double y0, double y1,
    const std::function<double(double, double)>& height = [](double, double) { return 0.0; }) {
  Mesh mesh;
  mesh.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = x0 + (x1 - x0) * i / nx;
      const double y = y0 + (y1 - y0) * j / ny;
      mesh.V.row(j * (nx + 1) + i) << x, y, height(x, y);
    }
  }
  mesh.F.resize(2 * nx * ny, 3);
  int f = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      if ((i + j) % 2 == 0) {
        mesh.F.row(f++) << a, b, d;
        mesh.F.row(f++) << a, d, c;
      } else {
        mesh.F.row(f++) << a, b, c;
        mesh.F.row(f++) << b, d, c;
      }
    }
  }
  return mesh;
}

// Icosahedron subdivided `levels` times, vertices projected onto the sphere of `radius` about the origin.
inline Mesh icosphere(int levels, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      midpoint[key] = static_cast<int>(v.size()) - 1;
      return static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> next;
    for (const auto& tri : f) {
      const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  Mesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    mesh.V.row(static_cast<Eigen::Index>(i)) = radius * v[i].transpose();
  mesh.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) mesh.F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return mesh;
}

// Open cylinder about the z axis: `around` vertices per ring, rings at z = 0 .. height.
inline Mesh cylinder(int around, int rings, double radius, double height) {
  Mesh mesh;
  mesh.V.resize(around * (rings + 1), 3);
  for (int r = 0; r <= rings; ++r) {
    for (int k = 0; k < around; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / around;
      mesh.V.row(r * around + k) << radius * std::cos(angle), radius * std::sin(angle), height * r / rings;
    }
  }
  mesh.F.resize(2 * around * rings, 3);
  int f = 0;
  for (int r = 0; r < rings; ++r) {
    for (int k = 0; k < around; ++k) {
      const int a = r * around + k, b = r * around + (k + 1) % around, c = a + around, d = b + around;
      mesh.F.row(f++) << a, b, d;
      mesh.F.row(f++) << a, d, c;
    }
  }
  return mesh;
}

}  // namespace pushpull::deform::testing
