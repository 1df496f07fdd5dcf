// The ARAP benchmark's cactus (Sorkine & Alexa data: .sel 0 fixed / 1 free / 2 handle, .def a 4x4 handle
// transform): every method gives finite output and a non-increasing energy.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

struct Cactus {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  ConstraintTargets targets;
};

Cactus load_cactus() {
  Cactus c;
  c.mesh = std::make_shared<const Mesh>(read_mesh(solver_testing::shared_mesh("cactus/cactus.off")));
  const std::vector<double> sel =
      solver_testing::read_numbers(solver_testing::shared_mesh("cactus/cactus.sel"));
  std::vector<int> selection(sel.begin(), sel.end());
  c.roi = roi_from_selection(*c.mesh, selection);
  const std::vector<double> def =
      solver_testing::read_numbers(solver_testing::shared_mesh("cactus/cactus.def"));
  if (def.size() != 16) throw std::runtime_error("cactus.def: expected 16 numbers");
  Eigen::Matrix4d T;
  for (int k = 0; k < 16; ++k) T(k / 4, k % 4) = def[static_cast<std::size_t>(k)];
  const Eigen::MatrixXd H = c.mesh->V(c.roi.handle, Eigen::all);
  c.targets.handle_positions =
      ((T.topLeftCorner<3, 3>() * H.transpose()).colwise() + T.topRightCorner<3, 1>()).transpose();
  return c;
}

class SolverCactus : public ::testing::TestWithParam<Method> {};

TEST_P(SolverCactus, FiniteAndEnergyDecreasing) {
  const Cactus c = load_cactus();
  ASSERT_EQ(c.roi.handle.size(), 87u);
  for (int window : {0, 5}) {  // plain local-global and Anderson-accelerated: both must be monotone
    DeformOptions options;
    options.method = GetParam();
    options.tolerance = 0;
    options.energy_tolerance = 0;
    options.max_iterations = 50;
    options.anderson_window = window;
    Deformer deformer(c.mesh, c.roi, options);
    const DeformResult r = deformer.solve(c.targets);
    ASSERT_TRUE(r.V.allFinite());
    ASSERT_EQ(r.iterations, 50);
    ASSERT_EQ(r.energy_trace.size(), 50u);
    double previous = r.initial_energy;
    for (double e : r.energy_trace) {
      EXPECT_LE(e, previous + 1e-9 * std::abs(previous)) << method_name(GetParam()) << " window " << window;
      previous = e;
    }
    EXPECT_LT(r.energy_trace.back(), 0.5 * r.initial_energy);
    // Handle vertices reached their targets; fixed ones did not move.
    EXPECT_LT((r.V(c.roi.handle, Eigen::all) - c.targets.handle_positions).norm(), 1e-12);
    EXPECT_LT((r.V(c.roi.fixed, Eigen::all) - c.mesh->V(c.roi.fixed, Eigen::all)).norm(), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(AllMethods, SolverCactus, ::testing::ValuesIn(kAllMethods), [](const auto& info) {
  std::string name(method_name(info.param));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
});

TEST(SolverCactusAnderson, ReachesPlainShapeInFewerIterations) {
  const Cactus c = load_cactus();
  for (Method method : {Method::ArapSR, Method::Asan}) {
    DeformOptions options;
    options.method = method;
    // Estimated distance to the minimiser, relative to the handle's move. Plain iterations crawl on the
    // stiff asan problem (about 5,000 iterations to 1.25e-2 here), hence the loose tolerance.
    options.tolerance = 2e-2;
    options.energy_tolerance = 0;
    options.max_iterations = 10000;
    options.anderson_window = 0;
    Deformer plain_deformer(c.mesh, c.roi, options);
    const DeformResult plain = plain_deformer.solve(c.targets);
    options.anderson_window = 6;
    Deformer accelerated_deformer(c.mesh, c.roi, options);
    const DeformResult accelerated = accelerated_deformer.solve(c.targets);
    ASSERT_TRUE(plain.converged) << method_name(method) << " estimate " << plain.error_estimate.value_or(-1)
                                 << " after " << plain.iterations;
    ASSERT_TRUE(accelerated.converged) << method_name(method);
    std::printf("%s: plain %d iterations, anderson %d iterations\n", std::string(method_name(method)).c_str(),
                plain.iterations, accelerated.iterations);
    EXPECT_LT(accelerated.iterations, plain.iterations) << method_name(method);
    const double reference =
        (c.targets.handle_positions - c.mesh->V(c.roi.handle, Eigen::all)).rowwise().norm().maxCoeff();
    // Same shape: each within its tolerance of the minimiser, so within twice it of each other.
    EXPECT_LT((plain.V - accelerated.V).rowwise().norm().maxCoeff(), 2 * options.tolerance * reference)
        << method_name(method);
    EXPECT_LE(accelerated.energy_trace.back(), plain.energy_trace.back() * 1.01);
  }
}

TEST(SolverCactus, CancelFromProgressCallback) {
  const Cactus c = load_cactus();
  DeformOptions options;
  options.method = Method::Asan;
  int calls = 0;
  options.progress = [&](const IterationReport& report) {
    ++calls;
    EXPECT_EQ(report.iteration, calls);
    EXPECT_TRUE(report.V != nullptr && report.V->allFinite());
    return report.iteration < 3;
  };
  Deformer deformer(c.mesh, c.roi, options);
  const DeformResult r = deformer.solve(c.targets);
  EXPECT_TRUE(r.cancelled);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason, StopReason::Cancelled);
  EXPECT_EQ(r.iterations, 3);
  EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace pushpull::deform
