// Regions above the solver's threading threshold (about 3,000 vertices) take the two-thread local step and
// split triangular solve. These tests run that path, so the sanitizer trees check it for races and bad
// accesses, and pin its results: deterministic, finite, energy never rising, constraints met.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

struct Problem {
  std::shared_ptr<const Mesh> mesh;
  std::vector<int> handle;
  std::vector<int> fixed;
};

// A 71 x 71 curved height field (5,041 vertices), handle = disk at the centre, fixed = the border.
Problem curved_sheet() {
  const int n = 70;
  Mesh mesh = solver_testing::sheet(n, n, 1.0, 1.0);
  Problem problem;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const double x = mesh.V(v, 0), y = mesh.V(v, 1);
    mesh.V(v, 2) = 0.08 * std::sin(M_PI * x) * std::sin(M_PI * y);
    const bool border = x < 1e-9 || y < 1e-9 || x > 1 - 1e-9 || y > 1 - 1e-9;
    if (border) problem.fixed.push_back(static_cast<int>(v));
    if (std::hypot(x - 0.5, y - 0.5) < 0.08) problem.handle.push_back(static_cast<int>(v));
  }
  problem.mesh = std::make_shared<const Mesh>(std::move(mesh));
  return problem;
}

DeformResult solve(const Problem& problem, Method method, const Eigen::Vector3d& d, int threads = 0) {
  DeformOptions options;
  options.method = method;
  options.threads = threads;
  Deformer deformer(problem.mesh, build_roi(*problem.mesh, problem.handle, problem.fixed), options);
  return deformer.solve(d);
}

class SolverThreaded : public ::testing::TestWithParam<Method> {};

TEST_P(SolverThreaded, LargeRegionIsDeterministicFiniteAndMonotone) {
  const Problem problem = curved_sheet();
  ASSERT_GT(problem.mesh->V.rows(), 5000);
  const Eigen::Vector3d d(0.05, 0.0, 0.15);
  const DeformResult first = solve(problem, GetParam(), d);
  const DeformResult second = solve(problem, GetParam(), d);

  ASSERT_TRUE(first.V.allFinite());
  EXPECT_EQ(first.iterations, second.iterations);
  EXPECT_EQ((first.V - second.V).cwiseAbs().maxCoeff(), 0.0) << "threaded solve is not deterministic";

  // The calling thread alone (as deform::Service solves) gives the same bits: the local step, the triangular
  // solves, Anderson's and the estimate's sums are split in the same fixed halves either way. (On a one-CPU
  // machine both solves run on one thread and this compares nothing: CI has two.)
  const DeformResult alone = solve(problem, GetParam(), d, /*threads=*/1);
  EXPECT_EQ(first.iterations, alone.iterations);
  EXPECT_EQ((first.V - alone.V).cwiseAbs().maxCoeff(), 0.0) << "one thread and two differ";
  EXPECT_EQ(first.error_estimate, alone.error_estimate);
  EXPECT_EQ(first.probe_rate, alone.probe_rate);  // the rate probe too, where it ran
  EXPECT_EQ(first.probe_evaluations, alone.probe_evaluations);

  for (int h : problem.handle) {
    EXPECT_NEAR((first.V.row(h) - problem.mesh->V.row(h)).norm(), d.norm(), 1e-9);
  }
  for (int f : problem.fixed) {
    EXPECT_EQ((first.V.row(f) - problem.mesh->V.row(f)).norm(), 0.0);
  }
  ASSERT_FALSE(first.energy_trace.empty());
  EXPECT_LT(first.energy_trace.back(), first.initial_energy);
  for (std::size_t k = 1; k < first.energy_trace.size(); ++k) {
    EXPECT_LE(first.energy_trace[k], first.energy_trace[k - 1] * (1 + 1e-9)) << "energy rose at iteration " << k;
  }
}

std::string test_name(const ::testing::TestParamInfo<Method>& info) {
  std::string name;
  for (char c : method_name(info.param)) {
    if (c != '-') name += c;  // gtest names are alphanumeric: arap-sr -> arapsr
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Methods, SolverThreaded, ::testing::Values(Method::ArapSR, Method::Asan, Method::ArapM),
                         test_name);

}  // namespace
}  // namespace pushpull::deform
