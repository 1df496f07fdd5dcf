// The replay report's camera for one push/pull (app/region_camera): it looks at the region from outside the
// model along the surface at the grabbed point, tilted off the up axis where the surface faces up, from far
// enough to hold the region in the picture.
#include "region_camera.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

using pushpull::app::region_camera;
using pushpull::deform::Mesh;

// The surface of the box [-2, 2] x [0, 1] x [-1, 1] (a car-sized block, y up), each face an n x n grid, faces
// wound outwards; vertices are not shared between faces (as tessellated CAD patches).
Mesh block(int n) {
  Mesh mesh;
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
  const Eigen::Vector3d low(-2, 0, -1), high(2, 1, 1);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int base = int(V.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          Eigen::Vector3d p;
          p[axis] = side ? high[axis] : low[axis];
          p[u] = low[u] + (high[u] - low[u]) * i / n;
          p[v] = low[v] + (high[v] - low[v]) * j / n;
          V.push_back(p);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
          if (side) {
            F.emplace_back(a, b, d), F.emplace_back(a, d, c);
          } else {
            F.emplace_back(a, d, b), F.emplace_back(a, c, d);
          }
        }
    }
  mesh.V.resize(Eigen::Index(V.size()), 3);
  for (std::size_t k = 0; k < V.size(); ++k) mesh.V.row(Eigen::Index(k)) = V[k].transpose();
  mesh.F.resize(Eigen::Index(F.size()), 3);
  for (std::size_t k = 0; k < F.size(); ++k) mesh.F.row(Eigen::Index(k)) = F[k].transpose();
  return mesh;
}

// The vertices within `radius` of `at`, and the one closest to it.
std::pair<std::vector<int>, int> region_near(const Mesh& mesh, const Eigen::Vector3d& at, double radius) {
  std::vector<int> region;
  int closest = -1;
  double best = 1e300;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const double r = (mesh.V.row(v).transpose() - at).norm();
    if (r <= radius) region.push_back(int(v));
    if (r < best) best = r, closest = int(v);
  }
  return {region, closest};
}

TEST(RegionCamera, LooksAtASideRegionAlongItsNormalFromOutside) {
  const Mesh mesh = block(8);
  // On the front face (+x), for a flip of the face's winding too.
  for (const bool flipped : {false, true}) {
    Mesh m = mesh;
    if (flipped) m.F.col(1).swap(m.F.col(2));
    const auto [region, grabbed] = region_near(m, Eigen::Vector3d(2, 0.5, 0), 0.4);
    ASSERT_FALSE(region.empty());
    const auto camera = region_camera(m, m.V, region, grabbed, Eigen::Vector3d::UnitY(), 30.0);
    ASSERT_TRUE(camera);
    const Eigen::Vector3d view = (camera->eye - camera->target).normalized();
    EXPECT_NEAR(view.x(), 1.0, 1e-9) << "flipped " << flipped;  // along +x, from outside the block
    EXPECT_GT(camera->eye.x(), 2.0);
    // Far enough that the region's bounding sphere fills 80% of half the vertical field of view.
    Eigen::AlignedBox3d box;
    for (const int v : region) box.extend(Eigen::Vector3d(m.V.row(v).transpose()));
    const double radius = 0.5 * box.diagonal().norm();
    const double distance = (camera->eye - camera->target).norm();
    EXPECT_NEAR(radius / distance, 0.8 * std::tan(15.0 * std::numbers::pi / 180.0), 1e-9);
    EXPECT_LT((camera->target - box.center()).norm(), 1e-12);
  }
}

TEST(RegionCamera, ATopRegionIsSeenFromAboveAndTheSideNotStraightDown) {
  const Mesh mesh = block(8);
  const auto [region, grabbed] = region_near(mesh, Eigen::Vector3d(1.5, 1.0, 0.0), 0.4);
  const auto camera = region_camera(mesh, mesh.V, region, grabbed, Eigen::Vector3d::UnitY(), 30.0);
  ASSERT_TRUE(camera);
  const Eigen::Vector3d view = (camera->eye - camera->target).normalized();
  EXPECT_GT(view.y(), 0.5);  // from above
  EXPECT_GT(view.x(), 0.3);  // and from the side the region lies on (+x), so up orients the picture
  EXPECT_LT(view.y(), 0.95);
}

TEST(RegionCamera, NoneWithoutARegion) {
  const Mesh mesh = block(2);
  EXPECT_FALSE(region_camera(mesh, mesh.V, {}, 0, Eigen::Vector3d::UnitY(), 30.0));
  EXPECT_FALSE(region_camera(mesh, mesh.V, {0, 1}, -1, Eigen::Vector3d::UnitY(), 30.0));
}

}  // namespace
