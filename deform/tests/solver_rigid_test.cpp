// A rigid motion of the whole region (handle and fixed vertices moved by the same rigid transform) is
// reproduced with near-zero energy by every method.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

class SolverRigid : public ::testing::TestWithParam<Method> {};

TEST_P(SolverRigid, RigidMotionHasZeroEnergy) {
  // A bumpy 16 x 16 sheet: curved, so the mean curvature term of arap-h and arap-sr-h is exercised.
  Mesh mesh = solver_testing::sheet(16, 16, 1.0, 1.0);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    mesh.V(v, 2) = 0.2 * std::sin(3.0 * mesh.V(v, 0)) * std::cos(2.0 * mesh.V(v, 1));
  }
  std::vector<int> handle, fixed;
  for (int v = 0; v < mesh.V.rows(); ++v) {
    if (mesh.V(v, 0) > 0.99) handle.push_back(v);
    if (mesh.V(v, 0) < 0.01) fixed.push_back(v);
  }
  auto shared = std::make_shared<const Mesh>(mesh);
  const RegionOfInterest roi = make_roi(mesh, handle, fixed, {});
  DeformOptions options;
  options.method = GetParam();
  options.max_iterations = 400;
  options.tolerance = 1e-10;
  options.energy_tolerance = 0;
  options.anderson_window = 5;
  Deformer deformer(shared, roi, options);

  const Eigen::Affine3d T =
      Eigen::Translation3d(0.3, -0.2, 0.5) * Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized());
  auto moved = [&](const Eigen::MatrixXd& P) -> Eigen::MatrixXd {
    const Eigen::Matrix3Xd Pt = P.transpose();
    return ((T.linear() * Pt).colwise() + T.translation()).transpose();
  };
  ConstraintTargets targets;
  targets.handle_positions = moved(mesh.V(roi.handle, Eigen::all));
  targets.fixed_positions = moved(mesh.V(roi.fixed, Eigen::all));
  const DeformResult result = deformer.solve(targets);

  const Eigen::MatrixXd expected = moved(mesh.V);
  ASSERT_FALSE(result.energy_trace.empty());
  EXPECT_GT(result.initial_energy, 1e-2);  // the initial guess (rest) was not rigid: the test can fail
  // arap-m's per-triangle rotations also allow isometric folds along edges at zero energy, so only the
  // per-vertex methods must find the rigid motion itself from the rest pose. arap-h adds to arap-m a term on
  // the mean curvature's magnitude that the folds change: from rest it settles in a folded local minimum
  // (here E = 3.6e-5 = 2.3e-6 E0, estimate 1e-10 after 776 iterations, 0.06 from the rigid motion), so it
  // gets a looser energy bound; the rigid motion itself is still its zero-energy fixed point (below).
  // sr-arap's coupled rotations (one Gauss-Seidel sweep per iteration) converge more slowly.
  const double energy_bound = GetParam() == Method::ArapH ? 1e-5 : 1e-6;
  EXPECT_LT(std::abs(result.energy_trace.back()), energy_bound * result.initial_energy)
      << method_name(GetParam());
  if (GetParam() != Method::ArapM && GetParam() != Method::ArapH) {
    const double tolerance = GetParam() == Method::SrArap ? 1e-3 : 1e-4;
    EXPECT_LT((result.V - expected).rowwise().norm().maxCoeff(), tolerance) << method_name(GetParam());
  }
  EXPECT_LT(std::abs(deformer.energy(expected)), 1e-10);
  // The rigid motion is a fixed point of every method.
  targets.initial_guess = expected;
  const DeformResult again = deformer.solve(targets);
  EXPECT_LT((again.V - expected).rowwise().norm().maxCoeff(), 1e-8) << method_name(GetParam());
  EXPECT_LT(std::abs(again.initial_energy), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, SolverRigid, ::testing::ValuesIn(kAllMethods), [](const auto& info) {
  std::string name(method_name(info.param));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
});

}  // namespace
}  // namespace pushpull::deform
