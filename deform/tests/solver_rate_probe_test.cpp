// The rate probe (src/rate_probe.hpp): on a linear map with one slow mode hidden among fast ones it finds
// the slow rate from inside the spectrum, and the solver probes only an early stop of a cold solve.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <random>

#include "../src/rate_probe.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

// J = I - M^-1 H with M diagonal (positive, uneven) and H = M^1/2 U diag(mu) U^T M^1/2: self-adjoint in
// the M inner product, eigenvalues 1 - mu. One mu is `slow` (rate 1 - slow), the others in [0.05, 1].
struct LinearMap {
  Eigen::VectorXd m;
  Eigen::MatrixXd J;
  LinearMap(int n, double slow) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    m.resize(n);
    for (int i = 0; i < n; ++i) m[i] = 0.2 + 5.0 * unit(rng);
    Eigen::MatrixXd random(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) random(i, j) = unit(rng) - 0.5;
    const Eigen::MatrixXd U = Eigen::HouseholderQR<Eigen::MatrixXd>(random).householderQ();
    Eigen::VectorXd mu(n);
    for (int i = 0; i < n; ++i) mu[i] = 0.05 + 0.95 * unit(rng);
    mu[n / 3] = slow;
    const Eigen::VectorXd root = m.cwiseSqrt();
    const Eigen::MatrixXd H = root.asDiagonal() * U * mu.asDiagonal() * U.transpose() * root.asDiagonal();
    J = Eigen::MatrixXd::Identity(n, n) - m.cwiseInverse().asDiagonal() * H;
  }
};

TEST(RateProbe, FindsTheSlowModeFromInsideTheSpectrum) {
  const LinearMap map(400, 1e-3);  // rate 0.999; the fast modes' rates are at most 0.95
  int metric_calls = 0;
  const detail::RateProbe probe = detail::probe_rate(
      400, 20, [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = map.J * v; },
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        ++metric_calls;
        out = map.m.cwiseProduct(v);
      });
  EXPECT_EQ(probe.evaluations, 20);
  EXPECT_LE(metric_calls, 21);  // once per basis vector
  EXPECT_GT(probe.rate, 0.998);
  EXPECT_LE(probe.rate, 0.999 + 1e-9);  // a Ritz value of a self-adjoint map: never above its largest
}

TEST(RateProbe, StopsWhenTheKrylovSpaceIsExhausted) {
  const detail::RateProbe probe = detail::probe_rate(
      50, 20, [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = 0.5 * v; },
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; });
  EXPECT_EQ(probe.evaluations, 1);
  EXPECT_NEAR(probe.rate, 0.5, 1e-12);
}

TEST(RateProbe, NonFiniteProductsEndTheProbe) {
  const detail::RateProbe probe = detail::probe_rate(
      50, 20, [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v * NAN; },
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; });
  EXPECT_EQ(probe.evaluations, 1);
  EXPECT_EQ(probe.rate, 0.0);
}

TEST(RateProbe, TheStartVectorIsFixedAndUnit) {
  const Eigen::VectorXd a = detail::probe_start(1000), b = detail::probe_start(1000);
  EXPECT_EQ(a, b);
  EXPECT_NEAR(a.norm(), 1.0, 1e-12);
  EXPECT_GT(a.maxCoeff(), 0.0);
  EXPECT_LT(a.minCoeff(), 0.0);
}

// A 21 x 21 flat sheet, border fixed, the centre vertex pulled up: arap-sr stops within a few windows.
struct SmallSheet {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  Eigen::Vector3d d{0.0, 0.0, 0.1};
  SmallSheet() {
    Mesh m = solver_testing::sheet(20, 20, 1.0, 1.0);
    std::vector<int> handle, fixed;
    for (int v = 0; v < m.V.rows(); ++v) {
      const double x = m.V(v, 0), y = m.V(v, 1);
      if (x < 1e-9 || y < 1e-9 || x > 1.0 - 1e-9 || y > 1.0 - 1e-9) fixed.push_back(v);
      if (std::hypot(x - 0.5, y - 0.5) <= 0.08) handle.push_back(v);
    }
    roi = make_roi(m, handle, fixed, {});
    mesh = std::make_shared<const Mesh>(std::move(m));
  }
};

TEST(SolverRateProbe, AnEarlyStopOfAColdSolveIsProbedOnce) {
  const SmallSheet s;
  DeformOptions options;
  options.method = Method::ArapSR;
  const DeformResult r = deform(*s.mesh, s.roi, s.d, options);
  ASSERT_TRUE(r.converged);
  ASSERT_LE(r.iterations, 32) << "the sheet no longer stops early: pick a problem that does";
  ASSERT_TRUE(r.probe_rate.has_value());
  EXPECT_GT(*r.probe_rate, 0.0);
  EXPECT_LT(*r.probe_rate, 1.0);
  EXPECT_GE(r.probe_evaluations, 2);   // G(X) and at least one Jacobian product
  EXPECT_LE(r.probe_evaluations, 21);  // one probe of at most 20 steps
  ASSERT_TRUE(r.contraction_rate.has_value());
  EXPECT_GE(*r.contraction_rate, *r.probe_rate);  // the probe's rate is a floor under the estimate
}

TEST(SolverRateProbe, AWarmStartWithARateHintAndThePaperSettingAreNotProbed) {
  const SmallSheet s;
  DeformOptions options;
  options.method = Method::ArapSR;
  Deformer deformer(s.mesh, s.roi, options);
  const DeformResult first = deformer.solve(0.9 * s.d);
  ConstraintTargets targets = deformer.push_pull_targets(s.d);
  targets.initial_guess = first.V;
  targets.rate_hint = first.contraction_rate;
  const DeformResult warm = deformer.solve(targets);
  ASSERT_TRUE(warm.converged);
  EXPECT_FALSE(warm.probe_rate.has_value());
  EXPECT_EQ(warm.probe_evaluations, 0);

  const DeformResult paper = deform(*s.mesh, s.roi, s.d, paper_iterations(options));
  EXPECT_FALSE(paper.probe_rate.has_value());
  EXPECT_EQ(paper.probe_evaluations, 0);
  EXPECT_EQ(paper.iterations, 50);
}

}  // namespace
}  // namespace pushpull::deform
