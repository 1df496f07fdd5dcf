// The Deformer's contract: preconditions, reuse of the factorization, ASAN refactorization when the
// direction changes, moved handles reach their targets, moves keep working after std::move.
#include <gtest/gtest.h>

#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

struct Dome {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  Dome() {
    Mesh m = solver_testing::sheet(20, 20, 1, 1);
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
      m.V(v, 2) = 0.3 - 0.6 * ((m.V(v, 0) - 0.5) * (m.V(v, 0) - 0.5) + (m.V(v, 1) - 0.5) * (m.V(v, 1) - 0.5));
    }
    std::vector<int> handle, fixed;
    for (int v = 0; v < m.V.rows(); ++v) {
      const int i = v % 21, j = v / 21;
      if (i == 0 || j == 0 || i == 20 || j == 20) fixed.push_back(v);
      if (std::abs(i - 10) <= 1 && std::abs(j - 10) <= 1) handle.push_back(v);
    }
    roi = make_roi(m, handle, fixed, {});
    mesh = std::make_shared<const Mesh>(std::move(m));
  }
};

void expect_invalid(const DeformOptions& options, const std::string& fragment) {
  const Dome dome;
  try {
    Deformer deformer(dome.mesh, dome.roi, options);
    FAIL() << "no exception, expected '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SolverDeformer, RejectsBadOptions) {
  DeformOptions o;
  o.mu = 1.0;
  expect_invalid(o, "mu");
  o = {};
  o.asan_base = Method::ArapS;
  expect_invalid(o, "asan_base");
  o = {};
  o.arap_n_rings = 0;
  expect_invalid(o, "arap_n_rings");
  o = {};
  o.tolerance = -1;
  expect_invalid(o, "tolerance");
  o = {};
  o.stretch_direction = Eigen::Vector3d::Zero();
  expect_invalid(o, "stretch_direction");
  o = {};
  o.anderson_window = -2;
  expect_invalid(o, "anderson_window");
}

TEST(SolverDeformer, RejectsMismatchedInputs) {
  const Dome dome;
  EXPECT_THROW(Deformer(nullptr, dome.roi), std::invalid_argument);
  RegionOfInterest short_roi = dome.roi;
  short_roi.role.pop_back();
  EXPECT_THROW(Deformer(dome.mesh, short_roi), std::invalid_argument);
  RegionOfInterest inconsistent = dome.roi;
  inconsistent.role[static_cast<std::size_t>(inconsistent.free.front())] = VertexRole::Outside;
  EXPECT_THROW(Deformer(dome.mesh, inconsistent), std::invalid_argument);
  Deformer deformer(dome.mesh, dome.roi);
  ConstraintTargets targets;
  targets.handle_positions = Eigen::MatrixXd::Zero(2, 3);
  EXPECT_THROW((void)deformer.solve(targets), std::invalid_argument);
  EXPECT_THROW((void)deformer.solve(Eigen::Vector3d(std::nan(""), 0, 0)), std::invalid_argument);
}

TEST(SolverDeformer, HandleMovesByDFixedStays) {
  const Dome dome;
  DeformOptions options;
  options.method = Method::Asan;
  Deformer deformer(dome.mesh, dome.roi, options);
  const Eigen::Vector3d d(0.0, 0.0, 0.15);
  const DeformResult r = deformer.solve(d);
  EXPECT_TRUE(r.converged) << stop_reason_name(r.stop_reason);
  EXPECT_EQ(static_cast<int>(r.energy_trace.size()), r.iterations);
  for (int h : dome.roi.handle) EXPECT_LT((r.V.row(h) - dome.mesh->V.row(h) - d.transpose()).norm(), 1e-14);
  for (int f : dome.roi.fixed) EXPECT_EQ(r.V.row(f), dome.mesh->V.row(f));
  EXPECT_GT(r.timing.factorize, 0.0);
  EXPECT_GT(r.timing.solve, 0.0);
  EXPECT_NEAR(deformer.energy(r.V), r.energy_trace.back(), 1e-9 * std::max(1.0, r.energy_trace.back()));
}

TEST(SolverDeformer, AsanRefactorsOnlyWhenTheDirectionChanges) {
  const Dome dome;
  Deformer deformer(dome.mesh, dome.roi, DeformOptions{});
  const DeformResult first = deformer.solve(Eigen::Vector3d(0, 0, 0.1));
  const DeformResult same_direction = deformer.solve(Eigen::Vector3d(0, 0, 0.2));
  const DeformResult opposite = deformer.solve(Eigen::Vector3d(0, 0, -0.1));  // tau depends on d d^T only
  const DeformResult other = deformer.solve(Eigen::Vector3d(0.1, 0, 0.1));
  EXPECT_TRUE(first.refactored);
  EXPECT_FALSE(same_direction.refactored);
  EXPECT_FALSE(opposite.refactored);
  EXPECT_TRUE(other.refactored);
  // The same request twice gives the same mesh (replay), also after other requests.
  const DeformResult again = deformer.solve(Eigen::Vector3d(0, 0, 0.1));
  EXPECT_EQ(again.V, first.V);
}

TEST(SolverDeformer, StretchDirectionChangesTheResult) {
  const Dome dome;
  DeformOptions along, across;
  across.stretch_direction = Eigen::Vector3d(1, 0, 0);  // d_o at 90 degrees to d (paper fig. 10)
  const DeformResult a = deform(*dome.mesh, dome.roi, Eigen::Vector3d(0, 0, 0.15), along);
  const DeformResult b = deform(*dome.mesh, dome.roi, Eigen::Vector3d(0, 0, 0.15), across);
  EXPECT_GT((a.V - b.V).rowwise().norm().maxCoeff(), 1e-3);
}

TEST(SolverDeformer, ZeroDisplacementKeepsRestPose) {
  const Dome dome;
  const DeformResult r = deform(*dome.mesh, dome.roi, Eigen::Vector3d::Zero());
  EXPECT_LT((r.V - dome.mesh->V).norm(), 1e-12);
  EXPECT_TRUE(r.converged);
  // A plain step that does not move is exact: the first iteration stops, with no probe.
  EXPECT_LE(r.iterations, 2);
  EXPECT_EQ(r.probe_evaluations, 0);
  ASSERT_TRUE(r.error_estimate.has_value());
  EXPECT_EQ(*r.error_estimate, 0.0);
  EXPECT_FALSE(r.warnings.empty());  // asan without a direction says it used plain weights
}

TEST(SolverDeformer, MovedDeformerStillSolves) {
  const Dome dome;
  Deformer a(dome.mesh, dome.roi);
  const DeformResult before = a.solve(Eigen::Vector3d(0, 0, 0.1));
  Deformer b = std::move(a);
  EXPECT_EQ(b.solve(Eigen::Vector3d(0, 0, 0.1)).V, before.V);
}

TEST(SolverDeformer, ExactIterationCountWhenTolerancesAreZero) {
  const Dome dome;
  DeformOptions options;
  options.tolerance = 0;
  options.energy_tolerance = 0;
  options.max_iterations = 7;
  const DeformResult r = deform(*dome.mesh, dome.roi, Eigen::Vector3d(0, 0, 0.1), options);
  EXPECT_EQ(r.iterations, 7);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason, StopReason::MaxIterations);
}

}  // namespace
}  // namespace pushpull::deform

namespace pushpull::deform {
namespace {

TEST(SolverDeformer, EverythingHandleIsATranslation) {
  const Mesh mesh = solver_testing::sheet(4, 4, 1, 1);
  std::vector<int> all(static_cast<std::size_t>(mesh.V.rows()));
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
  const RegionOfInterest roi = make_roi(mesh, all, {}, {});
  for (Method m : kAllMethods) {
    DeformOptions options;
    options.method = m;
    const DeformResult r = deform(mesh, roi, Eigen::Vector3d(1, 2, 3), options);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_LT((r.V.rowwise() - Eigen::RowVector3d(1, 2, 3) - mesh.V).norm(), 1e-14) << method_name(m);
  }
}

}  // namespace
}  // namespace pushpull::deform
