// The paper's shape claims, measured with the metrics on real solves (Le Vaou et al. 2020):
//  - Fig. 4 / 12: pulling the top of a hemisphere, ARAP-s&r makes Gaussian-curvature signs flip around the
//    handle (surface collapse), ASAN keeps them;
//  - Fig. 12a / 13: for an elongation (a pull along the surface), ASAN's displacement stays along d while
//    ARAP-s&r also moves vertices inside the section planes perpendicular to d.
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/deform/roi.hpp"
#include "test_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

namespace pd = pushpull::deform;
namespace pt = pushpull::deform::testing;

namespace {

std::vector<int> omega_of(const pd::RegionOfInterest& roi) {
  std::vector<int> omega;
  for (std::size_t i = 0; i < roi.role.size(); ++i) {
    if (roi.role[i] != pd::VertexRole::Outside) omega.push_back(static_cast<int>(i));
  }
  return omega;
}

pd::DeformationMetrics solve_and_measure(const std::shared_ptr<const pd::Mesh>& mesh,
                                         const pd::RegionOfInterest& roi, pd::Method method,
                                         const Eigen::Vector3d& d, int max_iterations) {
  pd::DeformOptions options;
  options.method = method;
  options.max_iterations = max_iterations;
  options.tolerance = 1e-4;
  options.energy_tolerance = 0.0;
  pd::Deformer deformer(mesh, roi, options);
  const pd::DeformResult result = deformer.solve(d);
  EXPECT_TRUE(result.V.allFinite());
  return pd::evaluate_deformation(*mesh, result.V, d, omega_of(roi));
}

}  // namespace

// hemisphere.off: unit hemisphere about +z, apex (0, 0, 1), open base ring at z ~ 0.098 (its mesh boundary).
// Handle: the cap z > 0.9; fixed: the base ring; d = (0, 0, pull).
TEST(MetricsClaims, HemispherePullFlipsFewerCurvatureSignsWithAsanThanWithArapSR) {
  auto mesh = std::make_shared<const pd::Mesh>(
      pd::read_mesh(std::filesystem::path(PUSHPULL_SHARED_DATA) / "meshes" / "hemisphere.off"));
  ASSERT_NEAR(mesh->V.col(2).maxCoeff(), 1.0, 1e-9);
  const pd::GaussianCurvature rest = pd::gaussian_curvature(mesh->V, mesh->F);
  std::vector<int> handle, fixed;
  for (int i = 0; i < mesh->V.rows(); ++i) {
    if (rest.boundary[static_cast<std::size_t>(i)]) fixed.push_back(i);
    if (mesh->V(i, 2) > 0.9) handle.push_back(i);
  }
  ASSERT_EQ(fixed.size(), 120u);
  const pd::RegionOfInterest roi = pd::build_roi(*mesh, handle, fixed);

  for (const double pull : {0.3, 0.5, 1.0}) {
    const Eigen::Vector3d d(0.0, 0.0, pull);
    const pd::DeformationMetrics arap = solve_and_measure(mesh, roi, pd::Method::ArapSR, d, 100);
    const pd::DeformationMetrics asan = solve_and_measure(mesh, roi, pd::Method::Asan, d, 100);
    // Before the pull every interior vertex of a sphere is elliptic.
    EXPECT_EQ(arap.positive_before, arap.curvature_vertices);
    // The comparison means something only if arap-sr does flip signs at this pull.
    EXPECT_GT(arap.sign_flip_fraction, 0.005) << "pull " << pull;
    EXPECT_LT(asan.sign_flip_fraction, 0.5 * arap.sign_flip_fraction)
        << "pull " << pull << ": asan " << asan.sign_flip_fraction << " vs arap-sr "
        << arap.sign_flip_fraction;
    RecordProperty("flip_fraction_arap_sr_pull_" + std::to_string(pull),
                   std::to_string(arap.sign_flip_fraction));
    RecordProperty("flip_fraction_asan_pull_" + std::to_string(pull),
                   std::to_string(asan.sign_flip_fraction));
  }
}

// A sheet over [0,1]^2, its left strip (x < 0.05) fixed, a handle patch on the right edge (x > 0.95,
// |y - 0.5| < 0.2) pulled along +x: an elongation as in the paper's Fig. 12a (hood) and Fig. 13.
class ElongationClaim : public ::testing::TestWithParam<double> {};

TEST_P(ElongationClaim, AsanMovesLessInsideTheSectionPlanesThanArapSR) {
  const double amplitude = GetParam();  // 0: flat; 0.1: gently curved across the pull, z = a sin(pi y)
  auto mesh = std::make_shared<const pd::Mesh>(pt::grid(
      30, 30, 0, 1, 0, 1, [&](double, double y) { return amplitude * std::sin(std::numbers::pi * y); }));
  std::vector<int> handle, fixed;
  for (int i = 0; i < mesh->V.rows(); ++i) {
    const double x = mesh->V(i, 0), y = mesh->V(i, 1);
    if (x < 0.05) fixed.push_back(i);
    if (x > 0.95 && std::abs(y - 0.5) < 0.2) handle.push_back(i);
  }
  const pd::RegionOfInterest roi = pd::build_roi(*mesh, handle, fixed);
  const Eigen::Vector3d d(0.2, 0.0, 0.0);
  const pd::DeformationMetrics arap = solve_and_measure(mesh, roi, pd::Method::ArapSR, d, 200);
  const pd::DeformationMetrics asan = solve_and_measure(mesh, roi, pd::Method::Asan, d, 200);
  // Both really elongate the sheet...
  EXPECT_GT(arap.along_d.rms, 0.05);
  EXPECT_GT(asan.along_d.rms, 0.05);
  // ...and arap-sr visibly moves vertices sideways (otherwise the comparison would say nothing)...
  EXPECT_GT(arap.orthogonal.rms, 0.002);
  // ...while asan's motion in the section planes is clearly smaller (RMS over the region, and the worst
  // vertex).
  EXPECT_LT(asan.orthogonal.rms, 0.5 * arap.orthogonal.rms)
      << "asan " << asan.orthogonal.rms << " arap-sr " << arap.orthogonal.rms;
  EXPECT_LT(asan.orthogonal.max, 0.5 * arap.orthogonal.max)
      << "asan " << asan.orthogonal.max << " arap-sr " << arap.orthogonal.max;
}

INSTANTIATE_TEST_SUITE_P(FlatAndCurved, ElongationClaim, ::testing::Values(0.0, 0.1));
