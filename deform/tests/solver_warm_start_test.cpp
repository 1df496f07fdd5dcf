// Warm starts (a drag's next request starts from the previous result): the error estimate stays honest when
// the previous solve's contraction rate is passed as ConstraintTargets::rate_hint, and a repeated request
// stops at once. Checked against a reference solved to 1e-9 |d|.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../src/error_estimate.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

// A 41 x 41 wavy sheet over [0, 1]^2 (1,681 vertices), border fixed, a disk of radius 0.1 at the centre as
// handle, pulled 0.1 up: deform_bench's problem at a test's size.
struct WavySheet : solver_testing::PulledSheet {
  WavySheet() : PulledSheet(solver_testing::pulled_sheet(40, 0.1, 0.05)) {}
};

double distance(const Eigen::MatrixXd& V, const Eigen::MatrixXd& reference, const Eigen::Vector3d& d) {
  return (V - reference).rowwise().norm().maxCoeff() / d.norm();
}

class WarmStart : public ::testing::TestWithParam<Method> {};

TEST_P(WarmStart, WithTheRateHintTheEstimateStaysHonest) {
  const WavySheet s;
  DeformOptions options;
  options.method = GetParam();
  DeformOptions tight = options;
  tight.tolerance = 1e-9;
  tight.max_iterations = 50000;
  const Eigen::MatrixXd reference = deform(*s.mesh, s.roi, s.d, tight).V;
  for (const double fraction : {0.9, 0.97, 0.995}) {
    Deformer deformer(s.mesh, s.roi, options);
    const DeformResult previous = deformer.solve(fraction * s.d);
    ASSERT_TRUE(previous.converged);
    ASSERT_TRUE(previous.contraction_rate.has_value());
    EXPECT_GE(*previous.contraction_rate, 0.0);
    EXPECT_LT(*previous.contraction_rate, 1.0);
    ConstraintTargets targets = deformer.push_pull_targets(s.d);
    targets.initial_guess = previous.V;
    targets.rate_hint = previous.contraction_rate;
    const DeformResult warm = deformer.solve(targets);
    ASSERT_TRUE(warm.converged) << "fraction " << fraction;
    ASSERT_TRUE(warm.error_estimate.has_value());
    const double error = distance(warm.V, reference, s.d);
    std::printf("%s, previous request %.3f d: %d iterations warm, estimate %.2e, true %.2e\n",
                method_name(GetParam()).data(), fraction, warm.iterations, *warm.error_estimate, error);
    EXPECT_LE(error, 2.0 * *warm.error_estimate) << "fraction " << fraction;
    EXPECT_LE(error, 2.0 * options.tolerance) << "fraction " << fraction;
  }
}

TEST_P(WarmStart, ARepeatedRequestStopsAtOnce) {
  const WavySheet s;
  DeformOptions options;
  options.method = GetParam();
  Deformer deformer(s.mesh, s.roi, options);
  const DeformResult first = deformer.solve(s.d);
  ASSERT_TRUE(first.converged);
  ConstraintTargets targets = deformer.push_pull_targets(s.d);
  targets.initial_guess = first.V;
  targets.rate_hint = first.contraction_rate;
  const DeformResult again = deformer.solve(targets);
  EXPECT_TRUE(again.converged);
  EXPECT_LE(again.iterations, 2);
  EXPECT_LE(distance(again.V, first.V, s.d), options.tolerance);
}

INSTANTIATE_TEST_SUITE_P(Methods, WarmStart, ::testing::Values(Method::Asan, Method::ArapSR),
                         [](const auto& info) {
                           return std::string(method_name(info.param)) == "asan" ? "Asan" : "ArapSR";
                         });

TEST(WarmStartHint, OutOfRangeHintsAreRefused) {
  const WavySheet s;
  Deformer deformer(s.mesh, s.roi, DeformOptions{});
  for (const double bad : {-0.1, 1.0, 2.0, std::nan("")}) {
    ConstraintTargets targets = deformer.push_pull_targets(s.d);
    targets.rate_hint = bad;
    EXPECT_THROW((void)deformer.solve(targets), std::invalid_argument) << bad;
  }
}

TEST(WarmStartHint, TheFloorBoundsTheRateFromBelowAndIsKnownAtOnce) {
  // A linear map with contraction 0.5 along every direction: the estimate sees 0.5; a floor of 0.9 wins.
  detail::ContractionEstimate plain(3, 4), floored(3, 4);
  floored.set_floor(0.9);
  EXPECT_FALSE(plain.rate().has_value());
  ASSERT_TRUE(floored.rate().has_value());
  EXPECT_DOUBLE_EQ(*floored.rate(), 0.9);
  Eigen::VectorXd x(4);
  x << 1.0, -2.0, 0.5, 3.0;
  for (int k = 0; k < 6; ++k) {
    const Eigen::VectorXd g = 0.5 * x;
    plain.add(x, g);
    floored.add(x, g);
    x = g + Eigen::VectorXd::Constant(4, 1e-3 * k);  // not exactly along one line
  }
  ASSERT_TRUE(plain.rate().has_value());
  EXPECT_NEAR(*plain.rate(), 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(*floored.rate(), 0.9);
  // Per-triangle rotations (Cautious) never stop on the hint alone.
  detail::ContractionEstimate cautious(3, 4, detail::ContractionEstimate::Policy::Cautious);
  cautious.set_floor(0.9);
  EXPECT_FALSE(cautious.rate().has_value());
}

TEST(ContractionRate, CountsOnceAFullWindowOfEstimatesHasBeenMade) {
  // Window 4 on G(x) = diag(0.5, 0.4, 0.3, 0.2) x: the first estimate comes with the fourth secant pair (the
  // fifth add), the rate only with the fourth estimate (the eighth add); a floor answers before, raised by
  // the estimates made so far. Four secant pairs span the space, so the largest Ritz value is G's 0.5.
  detail::ContractionEstimate plain(4, 4), floored(4, 4);
  floored.set_floor(0.2);
  const Eigen::Vector4d contraction(0.5, 0.4, 0.3, 0.2);
  Eigen::VectorXd x(4);
  x << 1.0, -2.0, 0.5, 3.0;
  for (int add = 1; add <= 8; ++add) {
    const Eigen::VectorXd g = contraction.cwiseProduct(x);
    plain.add(x, g);
    floored.add(x, g);
    x = g;
    EXPECT_EQ(plain.rate().has_value(), add >= 8) << add;
    ASSERT_TRUE(floored.rate().has_value()) << add;
    EXPECT_NEAR(*floored.rate(), add >= 5 ? 0.5 : 0.2, 1e-6) << add;
  }
}

}  // namespace
}  // namespace pushpull::deform
