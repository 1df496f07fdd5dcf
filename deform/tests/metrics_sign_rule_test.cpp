// The curvature sign rule (metrics.hpp): flat is |K| L^2 <= band with L the model's bounding-box diagonal,
// independent of the sharpest tiny part; flat panels are drawn flat; strict reversals are counted apart from
// moves into or out of flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/deform/roi.hpp"
#include "test_shapes.hpp"

namespace pd = pushpull::deform;
namespace pt = pushpull::deform::testing;

namespace {

// A 4 m x 2 m domed "body" panel (radii ~ 3 m and ~ 2 m) plus a separate 2 mm ball (a tiny
// part whose |K| ~ 1e6 / m^2 dominates any max).
pd::Mesh body_and_bolt() {
  const pd::Mesh body = pt::grid(
      40, 20, -2, 2, -1, 1, [](double x, double y) { return 0.6 - x * x / (2 * 3.0) - y * y / (2 * 2.0); });
  const pd::Mesh bolt = pt::icosphere(2, 0.002);
  pd::Mesh both;
  both.V.resize(body.V.rows() + bolt.V.rows(), 3);
  both.V << body.V, bolt.V.rowwise() + Eigen::RowVector3d(2.1, 0.0, 0.0);
  both.F.resize(body.F.rows() + bolt.F.rows(), 3);
  both.F << body.F, bolt.F.array() + static_cast<int>(body.V.rows());
  return both;
}

TEST(MetricsSignRule, BodyCurvatureIsSignedNextToATinySharpPart) {
  const pd::Mesh mesh = body_and_bolt();
  const pd::DeformationMetrics m = pd::evaluate_deformation(mesh, mesh.V, Eigen::Vector3d(1, 0, 0), {});
  const std::size_t body_interior = 39u * 19u;
  // K ~ 1 / (3 x 2) on the body, |K| L^2 ~ 3.5 with L ~ 4.6 m: elliptic, not flat (a dead band relative to
  // max |K| counted every body vertex flat because of the bolt).
  EXPECT_GE(m.positive_before, body_interior);
  EXPECT_EQ(m.negative_before, 0u);
  EXPECT_EQ(m.reference_length, pd::curvature_reference_length(mesh.V));
  // The rule this replaces, a dead band of 1e-3 x max |K|, calls the body flat.
  const pd::GaussianCurvature k = pd::gaussian_curvature(mesh.V, mesh.F);
  const auto old_signs = pd::curvature_signs(k, 1e-3 * k.K.cwiseAbs().maxCoeff());
  EXPECT_LT(std::count(old_signs.begin(), old_signs.begin() + 41 * 21, 1), 10);
  EXPECT_NEAR(m.curvature_threshold, pd::kDefaultFlatBand / (m.reference_length * m.reference_length), 1e-15);
}

TEST(MetricsSignRule, SameSignsAtEveryScale) {
  const pd::Mesh mesh = body_and_bolt();
  pd::Mesh toy = mesh;
  toy.V *= 0.018;  // a 7 cm toy of the same shape
  const pd::GaussianCurvature k = pd::gaussian_curvature(mesh.V, mesh.F);
  const pd::GaussianCurvature kt = pd::gaussian_curvature(toy.V, toy.F);
  const auto s = pd::curvature_signs(k, pd::flat_curvature_threshold(pd::curvature_reference_length(mesh.V)));
  const auto st =
      pd::curvature_signs(kt, pd::flat_curvature_threshold(pd::curvature_reference_length(toy.V)));
  EXPECT_EQ(s, st);
}

TEST(MetricsSignRule, StrictReversalsAreCountedApartFromMovesIntoAndOutOfFlat) {
  // An elliptic dome z = 0.3 (x^2 + y^2) becomes a saddle z = 0.3 (x^2 - y^2): every interior vertex
  // reverses; then the saddle flattens: every vertex goes into flat, none reverses.
  const auto dome = [](double x, double y) { return 0.3 * (x * x + y * y); };
  const pd::Mesh before = pt::grid(16, 16, -1, 1, -1, 1, dome);
  const pd::Mesh saddle =
      pt::grid(16, 16, -1, 1, -1, 1, [](double x, double y) { return 0.3 * (x * x - y * y); });
  const pd::Mesh plane = pt::grid(16, 16, -1, 1, -1, 1);
  const Eigen::Vector3d d(0, 0, 1);
  const std::size_t interior = 15u * 15u;

  const pd::DeformationMetrics reversed = pd::evaluate_deformation(before, saddle.V, d, {});
  EXPECT_EQ(reversed.positive_before, interior);
  EXPECT_EQ(reversed.sign_reversals, interior);
  EXPECT_EQ(reversed.into_flat + reversed.out_of_flat, 0u);
  EXPECT_DOUBLE_EQ(reversed.sign_reversal_fraction, 1.0);

  const pd::DeformationMetrics flattened = pd::evaluate_deformation(before, plane.V, d, {});
  EXPECT_EQ(flattened.sign_reversals, 0u);
  EXPECT_EQ(flattened.into_flat, interior);
  EXPECT_EQ(flattened.sign_flips, interior);  // the old "any change" count keeps its meaning
  EXPECT_DOUBLE_EQ(flattened.sign_reversal_fraction, 0.0);

  const pd::DeformationMetrics raised = pd::evaluate_deformation(plane, before.V, d, {});
  EXPECT_EQ(raised.out_of_flat, interior);
  EXPECT_EQ(raised.sign_reversals, 0u);
}

TEST(MetricsSignRule, ReversalsByBandTellGentleFromClearlyCurved) {
  // A gentle dome z = 0.05 (x^2 + y^2) (|K| ~ 0.01, |K| L^2 ~ 0.07 with L ~ 2.83) turned into the gentle
  // saddle reverses every interior vertex under the default band (1e-2) but none is signed under 0.1; the
  // dome z = 0.3 (x^2 + y^2) (|K| L^2 between about 1 and 2.9) turned into its saddle reverses under 0.1 and
  // 1 (partly), none is signed under 10.
  const std::size_t interior = 15u * 15u;
  const Eigen::Vector3d d(0, 0, 1);
  auto dome = [](double a) {
    return pt::grid(16, 16, -1, 1, -1, 1, [a](double x, double y) { return a * (x * x + y * y); });
  };
  auto saddle = [](double a) {
    return pt::grid(16, 16, -1, 1, -1, 1, [a](double x, double y) { return a * (x * x - y * y); });
  };

  const pd::DeformationMetrics gentle = pd::evaluate_deformation(dome(0.05), saddle(0.05).V, d, {});
  EXPECT_EQ(gentle.sign_reversals, interior);
  ASSERT_EQ(gentle.reversals_by_band.size(), 3u);
  EXPECT_EQ(gentle.reversals_by_band[0].band, 0.1);
  EXPECT_NEAR(gentle.reversals_by_band[0].radius_below, gentle.reference_length / std::sqrt(0.1), 1e-12);
  EXPECT_EQ(gentle.reversals_by_band[0].compared, 0u);
  EXPECT_EQ(gentle.reversals_by_band[0].reversals, 0u);

  const pd::DeformationMetrics strong = pd::evaluate_deformation(dome(0.3), saddle(0.3).V, d, {});
  EXPECT_EQ(strong.sign_reversals, interior);
  EXPECT_EQ(strong.reversals_by_band[0].compared, interior);
  EXPECT_EQ(strong.reversals_by_band[0].reversals, interior);
  // Under band 1 the flattest vertices (the corners' rings) are not signed; those signed all reverse.
  EXPECT_GT(strong.reversals_by_band[1].compared, interior / 4);
  EXPECT_LE(strong.reversals_by_band[1].reversals, strong.reversals_by_band[1].compared);
  EXPECT_GT(strong.reversals_by_band[1].reversals, 0u);
  EXPECT_EQ(strong.reversals_by_band[2].compared, 0u);
  // A clearly curved dome turned into a gentle saddle: every vertex signed under band 0.1 before has
  // reversed, though the saddle is too gentle to be signed under 0.1 (the sign after is the rule's own).
  const pd::DeformationMetrics softened = pd::evaluate_deformation(dome(0.3), saddle(0.05).V, d, {});
  EXPECT_EQ(softened.reversals_by_band[0].compared, interior);
  EXPECT_EQ(softened.reversals_by_band[0].reversals, interior);

  // A dome left as it is reverses nowhere, under any band; the bands are the caller's.
  pd::MetricsOptions options;
  options.reversal_bands = {0.5};
  const pd::DeformationMetrics kept = pd::evaluate_deformation(dome(0.3), dome(0.3).V, d, {}, options);
  ASSERT_EQ(kept.reversals_by_band.size(), 1u);
  EXPECT_GT(kept.reversals_by_band[0].compared, 0u);
  EXPECT_EQ(kept.reversals_by_band[0].reversals, 0u);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity()}) {
    options.reversal_bands = {bad};
    EXPECT_THROW((void)pd::evaluate_deformation(dome(0.3), dome(0.3).V, d, {}, options),
                 std::invalid_argument);
  }
}

// A cube of 12 triangles: 6 flat panels meeting at creases. Every vertex has the angle defect pi/2 of a
// corner, yet no face of the cube is curved.
pd::Mesh coarse_cube() {
  pd::Mesh cube;
  cube.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) cube.V.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  cube.F.resize(12, 3);
  cube.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5,
      3, 7, 5;
  return cube;
}

TEST(MetricsSignRule, FlatPanelsAreDrawnFlatAndCurvedSurfacesAreNot) {
  const pd::Mesh cube = coarse_cube();
  const pd::GaussianCurvature k = pd::gaussian_curvature(cube.V, cube.F);
  const auto signs =
      pd::curvature_signs(k, pd::flat_curvature_threshold(pd::curvature_reference_length(cube.V)));
  for (auto s : signs) ASSERT_EQ(s, 1);  // the corners are cone points
  const std::vector<bool> flat = pd::flat_panel_faces(cube.V, cube.F);
  for (bool f : flat) EXPECT_TRUE(f);
  for (auto s : pd::display_curvature_signs(signs, cube.F, flat)) EXPECT_EQ(s, 0);

  // A smooth sphere: no face is a flat panel, every vertex is drawn with its sign.
  const pd::Mesh ball = pt::icosphere(3, 1.0);
  const pd::GaussianCurvature kb = pd::gaussian_curvature(ball.V, ball.F);
  const auto ball_signs =
      pd::curvature_signs(kb, pd::flat_curvature_threshold(pd::curvature_reference_length(ball.V)));
  const std::vector<bool> ball_flat = pd::flat_panel_faces(ball.V, ball.F);
  for (bool f : ball_flat) EXPECT_FALSE(f);
  EXPECT_EQ(pd::display_curvature_signs(ball_signs, ball.F, ball_flat), ball_signs);

  // A plane with a bump: the faces far from the bump are flat panels (coplanar neighbours), the bump's
  // are not, and the bump's vertices keep their signs.
  const pd::Mesh bump = pt::grid(20, 20, -1, 1, -1, 1, [](double x, double y) {
    const double r2 = x * x + y * y;
    return r2 < 0.25 ? 0.1 * (0.25 - r2) * (0.25 - r2) * 16 : 0.0;
  });
  const std::vector<bool> bump_flat = pd::flat_panel_faces(bump.V, bump.F);
  int flat_faces = 0;
  for (Eigen::Index f = 0; f < bump.F.rows(); ++f) {
    const Eigen::Vector3d c =
        (bump.V.row(bump.F(f, 0)) + bump.V.row(bump.F(f, 1)) + bump.V.row(bump.F(f, 2))) / 3;
    if (c.head<2>().norm() > 0.75) {
      EXPECT_TRUE(bump_flat[static_cast<std::size_t>(f)]) << "face " << f;
    }
    if (c.head<2>().norm() < 0.3) {
      EXPECT_FALSE(bump_flat[static_cast<std::size_t>(f)]) << "face " << f;
    }
    flat_faces += bump_flat[static_cast<std::size_t>(f)];
  }
  EXPECT_GT(flat_faces, 0);
  const int centre = 10 * 21 + 10;
  const pd::GaussianCurvature kbump = pd::gaussian_curvature(bump.V, bump.F);
  const auto bump_signs =
      pd::curvature_signs(kbump, pd::flat_curvature_threshold(pd::curvature_reference_length(bump.V)));
  ASSERT_EQ(bump_signs[centre], 1);
  EXPECT_EQ(pd::display_curvature_signs(bump_signs, bump.F, bump_flat)[centre], 1);
}

}  // namespace

namespace {

// The hood example (scripts/demo-hood): the bundled bonnet's front edge pulled 10 cm forward. Its curvature is
// convex but gentle (|K| L^2 between 1e-2 and 1), so the default band must keep it signed for the paper's
// Fig. 12 finding to show: ARAP-s&r reverses part of it, ASAN none, and nothing of ASAN's goes flat.
TEST(MetricsSignRule, DefaultBandKeepsTheDemoBonnetFinding) {
  auto mesh = std::make_shared<const pd::Mesh>(
      pd::read_mesh(std::filesystem::path(PUSHPULL_SOURCE_DIR) / "examples" / "hood.off"));
  std::vector<int> handle;
  for (int v = 0; v < mesh->V.rows(); ++v) {
    if ((mesh->V.row(v) - Eigen::RowVector3d(0, 0, 0.9)).norm() <= 0.25) handle.push_back(v);
  }
  const pd::RegionOfInterest roi = pd::build_roi(*mesh, handle, {}, 0.9);
  std::vector<int> omega;
  for (std::size_t i = 0; i < roi.role.size(); ++i) {
    if (roi.role[i] != pd::VertexRole::Outside) omega.push_back(static_cast<int>(i));
  }
  const Eigen::Vector3d d(0, -0.1, 0);
  pd::DeformationMetrics m[2];
  for (int k = 0; k < 2; ++k) {
    pd::DeformOptions options;
    options.method = k == 0 ? pd::Method::Asan : pd::Method::ArapSR;
    const pd::DeformResult r = pd::deform(*mesh, roi, d, options);
    m[k] = pd::evaluate_deformation(*mesh, r.V, d, omega);
  }
  EXPECT_EQ(m[0].positive_before, m[0].curvature_vertices);  // all convex before
  EXPECT_EQ(m[0].sign_reversals, 0u);
  EXPECT_EQ(m[0].into_flat, 0u);
  EXPECT_GT(m[1].sign_reversal_fraction, 0.2);  // 28% once converged to 1e-2 |d|
}

}  // namespace
