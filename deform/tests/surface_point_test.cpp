// Handles grown along the surface from a surface point (issue: a Euclidean ball grabbed parts of other
// components lying close to the hit point).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pushpull/deform/surface_point.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform {
namespace {

// Two parallel unit sheets 1 cm apart (z = 0 and z = 0.01): separate components, like a lamp lens on a
// body panel or a dashboard behind a cab wall.
Mesh two_sheets() {
  return testing::append(testing::grid(20, 20, 0.0, 1.0, 0.0, 1.0),
                         testing::grid(20, 20, 0.0, 1.0, 0.0, 1.0, [](double, double) { return 0.01; }));
}

TEST(SurfacePoint, ClosestPointLiesInsideTheTriangleNotAtAVertex) {
  const Mesh m = testing::grid(4, 4, 0.0, 1.0, 0.0, 1.0);
  const SurfacePoint hit = closest_surface_point(m, Eigen::Vector3d(0.33, 0.41, 0.2));
  ASSERT_GE(hit.face, 0);
  EXPECT_NEAR(hit.point.x(), 0.33, 1e-12);
  EXPECT_NEAR(hit.point.y(), 0.41, 1e-12);
  EXPECT_NEAR(hit.point.z(), 0.0, 1e-12);
  // Outside the sheet: the closest point is on its border.
  const SurfacePoint edge = closest_surface_point(m, Eigen::Vector3d(1.5, 0.5, 0.0));
  EXPECT_NEAR(edge.point.x(), 1.0, 1e-12);
  EXPECT_NEAR(edge.point.y(), 0.5, 1e-12);
}

TEST(SurfacePoint, HandleStaysOnTheHitComponent) {
  const Mesh m = two_sheets();
  const SurfacePoint hit = closest_surface_point(m, Eigen::Vector3d(0.5, 0.5, -0.001));  // below sheet 1
  const std::vector<int> handle = surface_handle(m, hit, 0.1);
  ASSERT_FALSE(handle.empty());
  const int first_sheet = 21 * 21;
  EXPECT_TRUE(std::all_of(handle.begin(), handle.end(), [&](int v) { return v < first_sheet; }));
  // A Euclidean ball of the same radius would have taken vertices of both sheets.
  int ball_other = 0;
  for (Eigen::Index v = first_sheet; v < m.V.rows(); ++v)
    ball_other += (m.V.row(v).transpose() - hit.point).norm() <= 0.1;
  EXPECT_GT(ball_other, 0);
  // From above, the other sheet.
  const SurfacePoint top = closest_surface_point(m, Eigen::Vector3d(0.5, 0.5, 0.02));
  const std::vector<int> top_handle = surface_handle(m, top, 0.1);
  EXPECT_TRUE(std::all_of(top_handle.begin(), top_handle.end(), [&](int v) { return v >= first_sheet; }));
}

TEST(SurfacePoint, DistancesFollowTheSurfaceAroundAFold) {
  // A strip folded into a U: the two arms are 0.1 apart in space but 1 + 0.1 apart along the surface.
  Mesh m;
  const int n = 40;  // segments along the strip of length 2.1: arm (1), bottom (0.1), arm (1)
  m.V.resize(2 * (n + 1), 3);
  auto at = [](double s) -> Eigen::Vector2d {  // arc length -> (x, z)
    if (s <= 1.0) return {0.0, 1.0 - s};
    if (s <= 1.1) return {s - 1.0, 0.0};
    return {0.1, s - 1.1};
  };
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = at(2.1 * i / n);
    m.V.row(2 * i) << p.x(), 0.0, p.y();
    m.V.row(2 * i + 1) << p.x(), 0.05, p.y();
  }
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    m.F.row(2 * i) << 2 * i, 2 * i + 2, 2 * i + 1;
    m.F.row(2 * i + 1) << 2 * i + 1, 2 * i + 2, 2 * i + 3;
  }
  const SurfacePoint hit =
      closest_surface_point(m, Eigen::Vector3d(-0.01, 0.0, 0.9));  // near the top of arm 1
  const std::vector<int> handle = surface_handle(m, hit, 0.3);
  for (int v : handle) EXPECT_LT(m.V(v, 0), 0.05) << "vertex " << v << " is on the other arm";
  const std::vector<double> distance = surface_distances(m, hit);
  const int other_arm_top = 2 * n;  // (0.1, 0, 1): 0.1 away in space
  EXPECT_GT(distance[static_cast<std::size_t>(other_arm_top)], 1.0);
}

TEST(SurfacePoint, TinyRadiusTakesTheNearestCorner) {
  const Mesh m = testing::grid(4, 4, 0.0, 1.0, 0.0, 1.0);
  const SurfacePoint hit = closest_surface_point(m, Eigen::Vector3d(0.26, 0.24, 0.0));
  const std::vector<int> handle = surface_handle(m, hit, 1e-6);
  ASSERT_EQ(handle.size(), 1u);
  EXPECT_EQ(handle[0], 1 * 5 + 1);  // (0.25, 0.25)
}

TEST(SurfacePoint, BadInputIsRefused) {
  const Mesh m = testing::grid(2, 2, 0.0, 1.0, 0.0, 1.0);
  EXPECT_THROW((void)closest_surface_point(m, Eigen::Vector3d(std::nan(""), 0, 0)), std::invalid_argument);
  EXPECT_THROW((void)surface_handle(m, SurfacePoint{99, Eigen::Vector3d::Zero()}, 0.1),
               std::invalid_argument);
  EXPECT_THROW((void)surface_handle(m, SurfacePoint{0, Eigen::Vector3d::Zero()}, -1.0),
               std::invalid_argument);
  Mesh flat;
  flat.V = Eigen::MatrixXd::Zero(3, 3);
  flat.F.resize(1, 3);
  flat.F << 0, 1, 2;
  EXPECT_THROW((void)closest_surface_point(flat, Eigen::Vector3d::Zero()), std::invalid_argument);
}

// One graph serves many queries and shapes of the same faces: each answer equals the one-shot functions' on the
// same positions; positions of another vertex count are refused.
TEST(SurfacePoint, AGraphBuiltOnceAnswersAsTheOneShotFunctions) {
  Mesh m = testing::grid(9, 9, 0.0, 1.0, 0.0, 1.0);
  const SurfaceGraph graph(m);
  for (const double bend : {0.0, 0.3}) {
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) m.V(v, 2) = bend * m.V(v, 0) * m.V(v, 0);
    for (const int face : {0, 17, 60, int(m.F.rows()) - 1}) {
      const Eigen::Vector3d point =
          (m.V.row(m.F(face, 0)) + m.V.row(m.F(face, 1)) + 2.0 * m.V.row(m.F(face, 2))).transpose() / 4.0;
      const SurfacePoint from{face, point};
      EXPECT_EQ(graph.handle(m.V, from, 0.25), surface_handle(m, from, 0.25));
      EXPECT_EQ(graph.distances(m.V, from, 0.5), surface_distances(m, from, 0.5));
    }
  }
  EXPECT_THROW((void)graph.handle(m.V.topRows(10), SurfacePoint{0, Eigen::Vector3d::Zero()}, 0.1),
               std::invalid_argument);
}

}  // namespace
}  // namespace pushpull::deform

namespace pushpull::deform {
namespace {

// A point on an edge belongs to both triangles of the edge: the handle is the same whichever of them a ray
// hit or a closest-point search returned.
TEST(SurfacePoint, PointOnAnEdgeGivesTheSameHandleFromEitherTriangle) {
  const Mesh m = testing::grid(8, 8, 0.0, 1.0, 0.0, 1.0, [](double x, double y) { return 0.2 * x * y; });
  // The diagonal of cell (3, 3) is shared by its two triangles; take its midpoint.
  int first = -1, second = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int f = 0; f < m.F.rows() && second < 0; ++f) {
    for (int g = f + 1; g < m.F.rows() && second < 0; ++g) {
      int shared = 0;
      std::vector<int> common;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (m.F(f, i) == m.F(g, j)) ++shared, common.push_back(m.F(f, i));
      if (shared == 2 && m.V(common[0], 0) > 0.3 && m.V(common[0], 1) > 0.3) {
        first = f, second = g;
        point = 0.5 * (m.V.row(common[0]) + m.V.row(common[1])).transpose();
      }
    }
  }
  ASSERT_GE(second, 0);
  const std::vector<int> a = surface_handle(m, SurfacePoint{first, point}, 0.2);
  const std::vector<int> b = surface_handle(m, SurfacePoint{second, point}, 0.2);
  EXPECT_EQ(a, b);
  EXPECT_EQ(surface_distances(m, SurfacePoint{first, point}), surface_distances(m, SurfacePoint{second, point}));
}

}  // namespace
}  // namespace pushpull::deform
