// Parts lying on the solved surface (plates, lamps, trims) follow it whole; parts out of reach stay
// bit-identical.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>
#include <utility>

#include "pushpull/deform/attached_parts.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/triangle_bvh.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform {
namespace {

// A body panel (2 x 2 m, 40 x 40 cells), a plate 1 cm above its centre, a badge far away 1 cm above a
// corner, all separate components.
struct Scene {
  Mesh mesh;
  int body_vertices = 0, plate_first = 0, plate_count = 0, badge_first = 0, badge_count = 0;
};

Scene make_scene() {
  Scene s;
  const Mesh body = testing::grid(40, 40, -1.0, 1.0, -1.0, 1.0);
  const Mesh plate = testing::grid(4, 2, -0.2, 0.2, -0.05, 0.05, [](double, double) { return 0.01; });
  const Mesh badge = testing::grid(2, 2, 0.85, 0.95, 0.85, 0.95, [](double, double) { return 0.01; });
  s.body_vertices = static_cast<int>(body.V.rows());
  s.plate_first = s.body_vertices;
  s.plate_count = static_cast<int>(plate.V.rows());
  s.badge_first = s.plate_first + s.plate_count;
  s.badge_count = static_cast<int>(badge.V.rows());
  s.mesh = testing::append(testing::append(body, plate), badge);
  return s;
}

TEST(AttachedParts, PlateFollowsThePulledPanelAndKeepsItsGap) {
  const Scene s = make_scene();
  std::vector<int> handle;
  for (int v = 0; v < s.body_vertices; ++v)
    if (std::hypot(s.mesh.V(v, 0), s.mesh.V(v, 1)) < 0.15) handle.push_back(v);
  const RegionOfInterest roi = build_roi(s.mesh, handle, {}, 0.7);
  const AttachedParts parts(s.mesh, roi);
  ASSERT_EQ(parts.parts().size(), 1u);  // the plate; the badge is out of reach
  EXPECT_EQ(parts.parts()[0].vertices.front(), s.plate_first);
  EXPECT_EQ(parts.parts()[0].vertices.size(), static_cast<std::size_t>(s.plate_count));
  EXPECT_NEAR(parts.parts()[0].rest_gap, 0.01, 1e-12);

  DeformOptions options;
  options.method = Method::Asan;
  Deformer deformer(std::make_shared<const Mesh>(s.mesh), roi, options);
  Eigen::MatrixXd V = deformer.solve(Eigen::Vector3d(0.0, 0.0, 0.1)).V;
  // Without the binding the plate stays put and the panel passes through it.
  EXPECT_EQ(V.row(s.plate_first), s.mesh.V.row(s.plate_first));
  parts.apply(V);

  // Every plate vertex is still 1 cm above the moved panel (never sinks in), measured independently.
  const TriangleBvh body_tree(V, s.mesh.F, [&] {
    std::vector<int> faces;
    for (int f = 0; f < s.mesh.F.rows(); ++f)
      if (s.mesh.F(f, 0) < s.body_vertices) faces.push_back(f);
    return faces;
  }());
  for (int v = s.plate_first; v < s.plate_first + s.plate_count; ++v) {
    const auto hit = body_tree.closest_point(V, V.row(v).transpose());
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 0.01, 2e-3) << "plate vertex " << v;
    EXPECT_GT(V(v, 2), 0.05) << "plate vertex " << v << " did not follow the pull";
  }
  // Not torn: plate edges keep their lengths within a few percent.
  for (int f = 0; f < s.mesh.F.rows(); ++f) {
    if (s.mesh.F(f, 0) < s.plate_first || s.mesh.F(f, 0) >= s.badge_first) continue;
    for (int c = 0; c < 3; ++c) {
      const int a = s.mesh.F(f, c), b = s.mesh.F(f, (c + 1) % 3);
      const double before = (s.mesh.V.row(a) - s.mesh.V.row(b)).norm();
      const double after = (V.row(a) - V.row(b)).norm();
      EXPECT_NEAR(after / before, 1.0, 0.05);
    }
  }
  // Out of reach: bit-identical.
  for (int v = s.badge_first; v < s.badge_first + s.badge_count; ++v) EXPECT_EQ(V.row(v), s.mesh.V.row(v));
}

TEST(AttachedParts, PartOverAnUnmovedTriangleKeepsItsExactValues) {
  const Scene s = make_scene();
  std::vector<int> handle;
  for (int v = 0; v < s.body_vertices; ++v)
    if (std::hypot(s.mesh.V(v, 0) - 0.9, s.mesh.V(v, 1) - 0.9) < 0.08) handle.push_back(v);
  const RegionOfInterest roi = build_roi(s.mesh, handle, {}, 0.3);
  const AttachedParts parts(s.mesh, roi, {.reach = 0.02});
  ASSERT_EQ(parts.parts().size(), 1u);  // the badge now; the plate is out of reach
  EXPECT_EQ(parts.parts()[0].vertices.front(), s.badge_first);
  Eigen::MatrixXd V = s.mesh.V;  // nothing moved
  parts.apply(V);
  EXPECT_EQ(V, s.mesh.V);
}

// Grabbing a part itself (a windscreen, a lamp: the region is its whole component, no border to hold it)
// moves that part; the body under it is no part of it and stays. Before the body counted as a part lying near
// the region, every one of its vertices bound to the grabbed part, and it moved with it as one rigid piece.
TEST(AttachedParts, ABodyLargerThanTheRegionDoesNotFollowAGrabbedPart) {
  const Scene s = make_scene();
  std::vector<int> handle;
  for (int v = s.plate_first; v < s.plate_first + s.plate_count; ++v)
    if (std::abs(s.mesh.V(v, 0)) < 0.06) handle.push_back(v);
  const RegionOfInterest roi = build_roi(s.mesh, handle, {}, 1.0);  // the whole plate, nothing fixed
  const AttachedParts parts(s.mesh, roi);
  EXPECT_TRUE(parts.parts().empty());  // the body is 20x the plate; the badge is out of reach

  DeformOptions options;
  options.method = Method::Asan;
  Deformer deformer(std::make_shared<const Mesh>(s.mesh), roi, options);
  Eigen::MatrixXd V = deformer.solve(Eigen::Vector3d(0.0, 0.0, 0.1)).V;
  EXPECT_NEAR(V(s.plate_first, 2) - s.mesh.V(s.plate_first, 2), 0.1, 1e-9);  // the plate moved whole
  parts.apply(V);
  EXPECT_EQ(V.topRows(s.body_vertices), s.mesh.V.topRows(s.body_vertices));
}

TEST(AttachedParts, MismatchedRegionIsRefused) {
  const Scene s = make_scene();
  RegionOfInterest roi;
  roi.role.resize(3);
  EXPECT_THROW(AttachedParts(s.mesh, roi), std::invalid_argument);
}

TEST(TriangleBvh, ClosestPointAndRayHitAgreeWithBruteForce) {
  const Mesh m = testing::grid(30, 30, 0.0, 1.0, 0.0, 1.0,
                               [](double x, double y) { return 0.2 * std::sin(6 * x) * std::cos(5 * y); });
  const TriangleBvh tree(m.V, m.F);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(0.013 * k - 0.3, std::fmod(0.37 * k, 1.4) - 0.2, std::fmod(0.11 * k, 0.8) - 0.4);
    double brute = std::numeric_limits<double>::infinity();
    for (int f = 0; f < m.F.rows(); ++f) {
      const Eigen::Vector3d q =
          closest_point_on_triangle(p, m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2)));
      brute = std::min(brute, (q - p).norm());
    }
    const auto hit = tree.closest_point(m.V, p);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, brute, 1e-12);
    // A ray straight down from above hits the surface at (x, y) when inside the square.
    const Eigen::Vector3d origin(std::fmod(0.071 * k, 1.0), std::fmod(0.029 * k, 1.0), 5.0);
    const auto ray = tree.ray_hit(m.V, origin, Eigen::Vector3d(0, 0, -1));
    ASSERT_TRUE(ray);
    EXPECT_NEAR(ray->point.x(), origin.x(), 1e-12);
    EXPECT_NEAR(ray->point.y(), origin.y(), 1e-12);
    EXPECT_LT(std::abs(ray->point.z()), 0.21);
  }
  EXPECT_FALSE(tree.ray_hit(m.V, Eigen::Vector3d(2, 2, 5), Eigen::Vector3d(0, 0, -1)));
  EXPECT_FALSE(tree.closest_point(m.V, Eigen::Vector3d(0.5, 0.5, 3.0), 1.0));
  // Refit after a move: the hit follows.
  Eigen::MatrixXd moved = m.V;
  moved.col(2).array() += 1.0;
  TriangleBvh refitted = tree;
  refitted.refit(moved);
  const auto up = refitted.ray_hit(moved, Eigen::Vector3d(0.5, 0.5, 5.0), Eigen::Vector3d(0, 0, -1));
  ASSERT_TRUE(up);
  EXPECT_GT(up->point.z(), 0.75);
}

// Oblique rays (the headset's aim rays), hitting and missing: the first hit equals the brute-force nearest
// intersection over every triangle. (Before the fix of box pruning, a ray that had not hit yet visited every
// box; bvh_bench measures the time.)
TEST(TriangleBvh, ObliqueRaysFindTheNearestHitLikeBruteForce) {
  const Mesh m = testing::grid(40, 40, 0.0, 1.0, 0.0, 1.0,
                               [](double x, double y) { return 0.05 * std::sin(6 * x) * std::cos(5 * y); });
  const TriangleBvh tree(m.V, m.F);
  auto brute = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < m.F.rows(); ++f) {
      const Eigen::Vector3d a = m.V.row(m.F(f, 0)), e1 = Eigen::Vector3d(m.V.row(m.F(f, 1))) - a,
                            e2 = Eigen::Vector3d(m.V.row(m.F(f, 2))) - a;
      const Eigen::Vector3d pv = d.cross(e2);
      const double det = e1.dot(pv);
      if (det == 0.0) continue;
      const Eigen::Vector3d tv = o - a;
      const double u = tv.dot(pv) / det;
      const Eigen::Vector3d qv = tv.cross(e1);
      const double v = d.dot(qv) / det, t = e2.dot(qv) / det;
      if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t >= 0.0) best = std::min(best, t);
    }
    return best;
  };
  int hits = 0, misses = 0;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d origin(std::fmod(0.137 * k, 1.0), std::fmod(0.291 * k, 1.0), 0.3 + std::fmod(0.07 * k, 0.5));
    const double angle = 0.1 * k, slope = 0.2 + std::fmod(0.13 * k, 2.0);  // down 0.2 .. 2.2 per unit across
    const Eigen::Vector3d direction(std::cos(angle), std::sin(angle), -slope);
    const double expected = brute(origin, direction);
    const auto hit = tree.ray_hit(m.V, origin, direction);
    ASSERT_EQ(hit.has_value(), std::isfinite(expected)) << k;
    if (!hit) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(hit->distance, expected * direction.norm(), 1e-12) << k;
  }
  EXPECT_GT(hits, 20);
  EXPECT_GT(misses, 20);
}

}  // namespace
}  // namespace pushpull::deform

namespace pushpull::deform {
namespace {

TEST(AttachedParts, NothingToBindLeavesPositionsAlone) {
  const Mesh m = testing::grid(6, 6, 0.0, 1.0, 0.0, 1.0);
  const RegionOfInterest roi = build_roi(m, std::vector<int>{24}, {}, 0.3);
  const AttachedParts parts(m, roi);
  EXPECT_TRUE(parts.parts().empty());
  Eigen::MatrixXd V = m.V;
  V(24, 2) = 0.1;
  parts.apply(V);
  EXPECT_EQ(V(24, 2), 0.1);
  const AttachedParts empty;
  EXPECT_THROW(empty.apply(V), std::invalid_argument);  // made for no mesh
}

// A part high above a finely tessellated panel (1 cm cells, the part 10 cm up) does not amplify the solve's
// error: a ripple on the panel (what an unconverged solve leaves: 1e-4 m high, 10 cm long) tilts a patch of a
// triangle's corners and their neighbours, which swung the part by 3.8e-4 m; the patch grown as wide as the
// part is high averages the ripple (6.8e-5 m).
TEST(AttachedParts, APartFarAboveFineTrianglesMovesNoMoreThanTheSurfaceErrs) {
  const Mesh body = testing::grid(100, 100, -0.5, 0.5, -0.5, 0.5);
  const Mesh part = testing::grid(2, 2, -0.0363, 0.0637, -0.0429, 0.0571, [](double, double) { return 0.1; });
  const int body_vertices = static_cast<int>(body.V.rows());
  const Mesh mesh = testing::append(body, part);
  std::vector<int> handle;
  for (int v = 0; v < body_vertices; ++v)
    if (std::hypot(mesh.V(v, 0), mesh.V(v, 1)) < 0.1) handle.push_back(v);
  const RegionOfInterest roi = build_roi(mesh, handle, {}, 0.35);
  const AttachedParts parts(mesh, roi, {.reach = 0.15});
  ASSERT_EQ(parts.parts().size(), 1u);
  ASSERT_TRUE(parts.parts()[0].on_surface);

  // The surface moved smoothly (a bump 5 cm high), and the same with the ripple on top.
  const double ripple = 1e-4;
  Eigen::MatrixXd smooth = mesh.V, rippled = mesh.V;
  for (int v = 0; v < body_vertices; ++v) {
    if (roi.role[static_cast<std::size_t>(v)] == VertexRole::Outside) continue;
    const double x = mesh.V(v, 0), y = mesh.V(v, 1);
    const double bump = 0.05 * std::exp(-(x * x + y * y) / (2.0 * 0.15 * 0.15));
    smooth(v, 2) += bump;
    rippled(v, 2) += bump + ripple * std::sin(2.0 * std::numbers::pi * x / 0.1 + 0.7) *
                                std::sin(2.0 * std::numbers::pi * y / 0.1 + 0.3);
  }
  parts.apply(smooth);
  parts.apply(rippled);
  for (int v = body_vertices; v < mesh.V.rows(); ++v) {
    EXPECT_GT(smooth(v, 2), 0.14) << "part vertex " << v << " did not follow the bump";
    EXPECT_LT((rippled.row(v) - smooth.row(v)).norm(), 1.5 * ripple) << "part vertex " << v;
  }
}

// A 2 x 2 m panel of 5 cm cells with `part` above it, the region grown `region_radius` along the surface from
// the panel's vertices within 10 cm of its centre.
struct PanelScene {
  Mesh mesh;
  int body_vertices = 0;
  RegionOfInterest roi;
};

PanelScene panel_with(const Mesh& part, double region_radius) {
  PanelScene s;
  const Mesh body = testing::grid(40, 40, -1.0, 1.0, -1.0, 1.0);
  s.body_vertices = static_cast<int>(body.V.rows());
  s.mesh = testing::append(body, part);
  std::vector<int> handle;
  for (int v = 0; v < s.body_vertices; ++v)
    if (std::hypot(s.mesh.V(v, 0), s.mesh.V(v, 1)) < 0.1) handle.push_back(v);
  s.roi = build_roi(s.mesh, handle, {}, region_radius);
  return s;
}

// The scene's positions with the region's handle and free vertices raised by height(x, y), the rest at rest.
Eigen::MatrixXd raised(const PanelScene& s, const std::function<double(double, double)>& height) {
  Eigen::MatrixXd V = s.mesh.V;
  for (int v = 0; v < s.body_vertices; ++v) {
    const VertexRole role = s.roi.role[static_cast<std::size_t>(v)];
    if (role == VertexRole::Free || role == VertexRole::Handle) V(v, 2) += height(V(v, 0), V(v, 1));
  }
  return V;
}

// A part just outside the region, over a panel the solve left byte-identical, stays exactly put: the patch
// grown for its rotation (10 cm above 5 cm cells: four rings) reaches into the moved region, and deciding
// "moved" on that patch swung the part with the bump next to it; the carrier's corners and their neighbours
// decide instead.
TEST(AttachedParts, APartBesideTheRegionOverAnUnmovedPanelStaysExactlyPut) {
  const PanelScene s =
      panel_with(testing::grid(2, 2, 0.42, 0.48, -0.03, 0.03, [](double, double) { return 0.1; }), 0.3);
  const AttachedParts parts(s.mesh, s.roi, {.reach = 0.2});
  ASSERT_EQ(parts.parts().size(), 1u);
  ASSERT_TRUE(parts.parts()[0].on_surface);
  const auto bump = [](double x, double y) { return 0.05 * std::exp(-(x * x + y * y) / (2.0 * 0.1 * 0.1)); };
  Eigen::MatrixXd V = raised(s, bump);
  int moved = 0;  // within the part's grown patch
  for (int v = 0; v < s.body_vertices; ++v)
    moved += V(v, 2) != s.mesh.V(v, 2) && std::hypot(s.mesh.V(v, 0) - 0.45, s.mesh.V(v, 1)) < 0.25 ? 1 : 0;
  ASSERT_GT(moved, 0);
  parts.apply(V);
  for (int v = s.body_vertices; v < s.mesh.V.rows(); ++v)
    EXPECT_EQ(V.row(v), s.mesh.V.row(v)) << "part vertex " << v;

  // The part's carrier triangles have corners at x = 0.40, 0.45 and 0.50 (straight under it): a neighbour of
  // a corner (x = 0.55) moved alone moves the part; a vertex three rings out (x = 0.65), though within the
  // grown patches, does not.
  auto vertex_at = [&](double x, double y) {
    for (int v = 0; v < s.body_vertices; ++v)
      if (std::abs(s.mesh.V(v, 0) - x) < 1e-9 && std::abs(s.mesh.V(v, 1) - y) < 1e-9) return v;
    return -1;
  };
  for (const auto& [x, follows] : {std::pair{0.55, true}, std::pair{0.65, false}}) {
    Eigen::MatrixXd U = s.mesh.V;
    const int v = vertex_at(x, 0.0);
    ASSERT_GE(v, 0);
    U(v, 2) += 0.01;
    parts.apply(U);
    EXPECT_EQ(U.bottomRows(U.rows() - s.body_vertices) != s.mesh.V.bottomRows(U.rows() - s.body_vertices),
              follows)
        << "x = " << x;
  }

  // Over the moved panel the same part follows it.
  Mesh shifted = s.mesh;
  for (int v = s.body_vertices; v < s.mesh.V.rows(); ++v) shifted.V(v, 0) -= 0.4;
  const AttachedParts over(shifted, s.roi, {.reach = 0.2});
  Eigen::MatrixXd W = shifted.V;
  W.topRows(s.body_vertices) = V.topRows(s.body_vertices);
  over.apply(W);
  for (int v = s.body_vertices; v < s.mesh.V.rows(); ++v) EXPECT_GT(W(v, 2), 0.12) << "part vertex " << v;
}

// A trim lying along a bulge and across the region's border (2 cm above a smooth bump pulled 8 cm, 5 cm
// cells, the trim's vertices 1.5 cm apart) bends with the surface instead of stepping: each triangle's offset
// turns by its corners' rotations blended across it. Turned by one rotation per triangle, the trim shifted
// along itself in steps where its vertices changed triangles (second differences of its in-plane
// displacement up to 1.7 mm; blended 0.25 mm, about what the bump's own curvature gives).
TEST(AttachedParts, ATrimAlongABulgeBendsWithoutSteps) {
  const PanelScene s =
      panel_with(testing::grid(40, 1, 0.1, 0.7, -0.01, 0.01, [](double, double) { return 0.02; }), 0.4);
  const AttachedParts parts(s.mesh, s.roi, {.reach = 0.1});
  ASSERT_EQ(parts.parts().size(), 1u);
  ASSERT_TRUE(parts.parts()[0].on_surface);
  Eigen::MatrixXd V = raised(s, [](double x, double y) {
    const double t = std::max(0.0, 1.0 - (x * x + y * y) / (0.42 * 0.42));
    return 0.08 * t * t;
  });
  parts.apply(V);
  // Along each of the trim's two rows of 41 vertices.
  double worst = 0.0;
  for (int row = 0; row < 2; ++row)
    for (int i = 1; i < 40; ++i) {
      const int v = s.body_vertices + row * 41 + i;
      auto shift = [&](int w) -> Eigen::Vector2d {
        return (V.row(w) - s.mesh.V.row(w)).head<2>().transpose();
      };
      worst = std::max(worst, (shift(v - 1) - 2.0 * shift(v) + shift(v + 1)).norm());
    }
  EXPECT_LT(worst, 5e-4);
  EXPECT_GT(V(s.body_vertices, 2) - s.mesh.V(s.body_vertices, 2),
            0.06);  // the trim's inner end rose with the bump
  EXPECT_EQ(V.row(s.body_vertices + 40), s.mesh.V.row(s.body_vertices + 40));  // its outer end stayed
}

}  // namespace
}  // namespace pushpull::deform
