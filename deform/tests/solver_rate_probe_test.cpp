// The rate probe (src/rate_probe.hpp): on a linear map with one slow mode hidden among fast ones it finds
// the slow rate from inside the spectrum, and the solver probes only an early stop of a cold solve, and can
// be cancelled during it. The estimate's rate (src/error_estimate.hpp): the later half of the solve's
// largest, the warm start's rate the last ten's.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <random>

#include "../src/error_estimate.hpp"
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
      400, 20,
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = map.J * v;
        return true;
      },
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        ++metric_calls;
        out = map.m.cwiseProduct(v);
      });
  EXPECT_EQ(probe.evaluations, 20);
  EXPECT_LE(metric_calls, 3 * 20 + 1);  // the start, then two Gram-Schmidt passes and a norm per step
  EXPECT_GT(probe.rate, 0.998);
  EXPECT_LE(probe.rate, 0.999 + 1e-9);  // a Ritz value of a self-adjoint map: never above its largest
}

// A hint along the solve's last step points the probe at the slow mode that holds a stalled solve: 200
// iterations of the map leave the fast modes (rates <= 0.95) at 3.5e-5 of their start and the slow one
// (0.999) at 0.82, so the last step lies along it; 4 steps from the random start alone stay in the fast
// cluster (0.894), from the random start plus the last step they reach 0.9952 (the solver's floor from it:
// 0.9976).
TEST(RateProbe, AHintAlongTheLastStepFindsTheModeThatHoldsAStall) {
  const LinearMap map(400, 1e-3);
  auto jacobian = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    out = map.J * v;
    return true;
  };
  auto metric = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = map.m.cwiseProduct(v); };
  Eigen::VectorXd x = detail::probe_start(400), previous = x;
  for (int k = 0; k < 200; ++k) previous = x, x = map.J * x;
  const Eigen::VectorXd last_step = x - previous;
  EXPECT_LT(detail::probe_rate(400, 4, jacobian, metric).rate, 0.95);  // 0.894
  EXPECT_LT(detail::probe_rate_self_adjoint(400, 4, jacobian, metric).rate, 0.95);
  EXPECT_GT(detail::probe_rate(400, 4, jacobian, metric, nullptr, &last_step).rate, 0.99);  // 0.9952
  EXPECT_GT(detail::probe_rate_self_adjoint(400, 4, jacobian, metric, &last_step).rate, 0.99);
  // Still a Ritz value of the map: never above its largest.
  EXPECT_LE(detail::probe_rate_self_adjoint(400, 4, jacobian, metric, &last_step).rate, 0.999 + 1e-9);
}

// The Lanczos recurrence on the same self-adjoint map: Arnoldi's rate (the same Krylov space, the same
// projection in exact arithmetic), one metric product per step.
TEST(RateProbe, LanczosReadsArnoldisRateOnASelfAdjointMap) {
  const LinearMap map(400, 1e-3);
  auto jacobian = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    out = map.J * v;
    return true;
  };
  int metric_calls = 0;
  auto metric = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    ++metric_calls;
    out = map.m.cwiseProduct(v);
  };
  for (const int steps : {10, 20, 40}) {
    const detail::RateProbe arnoldi = detail::probe_rate(400, steps, jacobian, metric);
    metric_calls = 0;
    const detail::RateProbe lanczos = detail::probe_rate_self_adjoint(400, steps, jacobian, metric);
    EXPECT_EQ(lanczos.evaluations, steps);
    EXPECT_EQ(metric_calls, steps);  // the start's, then one per step but the last
    EXPECT_NEAR(lanczos.rate, arnoldi.rate, 1e-9) << steps << " steps";
    EXPECT_LE(lanczos.rate, 0.999 + 1e-9);
  }
  EXPECT_GT(detail::probe_rate_self_adjoint(400, 20, jacobian, metric).rate, 0.998);
}

// The same stops as Arnoldi: an exhausted Krylov space, a non-finite product, a Jacobian that says stop.
TEST(RateProbe, LanczosStopsAsArnoldiDoes) {
  auto identity = [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; };
  const detail::RateProbe exhausted = detail::probe_rate_self_adjoint(
      50, 20,
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = 0.5 * v;
        return true;
      },
      identity);
  EXPECT_EQ(exhausted.evaluations, 1);
  EXPECT_NEAR(exhausted.rate, 0.5, 1e-12);
  const detail::RateProbe not_finite = detail::probe_rate_self_adjoint(
      50, 20,
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = v * NAN;
        return true;
      },
      identity);
  EXPECT_EQ(not_finite.evaluations, 1);
  EXPECT_EQ(not_finite.rate, 0.0);
  int calls = 0;
  const detail::RateProbe abandoned = detail::probe_rate_self_adjoint(
      50, 20,
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = Eigen::VectorXd::LinSpaced(v.size(), 0.1, 0.9).cwiseProduct(v);
        return ++calls < 3;
      },
      identity);
  EXPECT_TRUE(abandoned.abandoned);
  EXPECT_EQ(abandoned.evaluations, 2);
  EXPECT_EQ(abandoned.rate, 0.0);
}

TEST(RateProbe, StopsWhenTheKrylovSpaceIsExhausted) {
  const detail::RateProbe probe = detail::probe_rate(
      50, 20,
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = 0.5 * v;
        return true;
      },
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; });
  EXPECT_EQ(probe.evaluations, 1);
  EXPECT_NEAR(probe.rate, 0.5, 1e-12);
}

TEST(RateProbe, NonFiniteProductsEndTheProbe) {
  const detail::RateProbe probe = detail::probe_rate(
      50, 20,
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = v * NAN;
        return true;
      },
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; });
  EXPECT_EQ(probe.evaluations, 1);
  EXPECT_EQ(probe.rate, 0.0);
}

TEST(RateProbe, AJacobianThatSaysStopAbandonsIt) {
  int calls = 0;
  const detail::RateProbe probe = detail::probe_rate(
      50, 20,
      [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
        out = Eigen::VectorXd::LinSpaced(v.size(), 0.1, 0.9).cwiseProduct(v);  // 50 distinct rates
        return ++calls < 3;
      },
      [](const Eigen::VectorXd& v, Eigen::VectorXd& out) { out = v; });
  EXPECT_TRUE(probe.abandoned);
  EXPECT_EQ(probe.evaluations, 2);
  EXPECT_EQ(probe.rate, 0.0);
}

// Secant pairs of a linear map J (dG = J dX exactly; 8 dimensions = the window, so the Ritz values are J's
// eigenvalues): a slow phase (largest rate 0.99), then a fast one (0.5).
struct TwoPhaseMap {
  static constexpr int n = 8;
  Eigen::VectorXd slow{{0.99, 0.5, 0.4, 0.3, 0.2, 0.1, -0.2, 0.05}};
  Eigen::VectorXd fast{{0.5, 0.45, 0.4, 0.3, 0.2, 0.1, -0.2, 0.05}};
  std::mt19937 rng{3};
  // `count` iterates x (random) and G(x) = diag(eigenvalues) x into `estimate`.
  void feed(detail::ContractionEstimate& estimate, const Eigen::VectorXd& eigenvalues, int count) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int k = 0; k < count; ++k) {
      Eigen::VectorXd x(n);
      for (int i = 0; i < n; ++i) x[i] = unit(rng);
      estimate.add(x, eigenvalues.cwiseProduct(x));
    }
  }
};

TEST(ContractionEstimate, TheLaterHalfKeepsASlowRateTheLastTenForget) {
  TwoPhaseMap map;
  detail::ContractionEstimate estimate(8, TwoPhaseMap::n);
  const Eigen::VectorXd &slow = map.slow, &fast = map.fast;
  auto feed = [&](const Eigen::VectorXd& eigenvalues, int count) { map.feed(estimate, eigenvalues, count); };
  feed(slow, 40);  // estimates from iteration 9 on: 32 of them, all 0.99
  ASSERT_TRUE(estimate.rate().has_value());
  EXPECT_NEAR(*estimate.rate(), 0.99, 1e-6);
  EXPECT_NEAR(*estimate.recent_rate(), 0.99, 1e-6);
  // 52 estimates: the last 12 see only the fast phase (8 pairs each); those whose pairs straddle the change
  // are no map's Ritz values and may be anything (clamped to kMaxRate).
  feed(fast, 20);
  EXPECT_GE(*estimate.rate(), 0.99 - 1e-6) << "the later half still holds the slow phase";
  EXPECT_NEAR(*estimate.recent_rate(), 0.5, 1e-6) << "the last 10 estimates have forgotten it";
  feed(fast, 80);  // 132 estimates: the later half is all fast
  EXPECT_NEAR(*estimate.rate(), 0.5, 1e-6);
}

// Near a minimiser the local-global map's Jacobian has real eigenvalues in [0, 1] (error_estimate.hpp): a
// Ritz value with a non-positive real part or a modulus >= 1 is noise and does not set the rate (Recent,
// Warm). Cautious counts every value.
TEST(ContractionEstimate, RitzValuesWithANonPositiveRealPartDoNotSetTheRate) {
  using Policy = detail::ContractionEstimate::Policy;
  TwoPhaseMap map;
  const Eigen::VectorXd negative{{0.9, 0.5, 0.4, 0.3, 0.2, 0.1, -1.5, -0.95}};
  detail::ContractionEstimate recent(8, TwoPhaseMap::n), warm(8, TwoPhaseMap::n, Policy::Warm),
      cautious(8, TwoPhaseMap::n, Policy::Cautious);
  warm.set_floor(0.2);
  for (auto* estimate : {&recent, &warm, &cautious}) map.feed(*estimate, negative, 40);
  ASSERT_TRUE(recent.rate().has_value());
  EXPECT_NEAR(*recent.rate(), 0.9, 1e-6) << "-1.5 and -0.95 are left out";
  EXPECT_NEAR(*warm.rate(), 0.9, 1e-6);
  EXPECT_FALSE(cautious.rate().has_value()) << "Cautious reads |-1.5| >= 1 as iterates moving away";

  const Eigen::VectorXd above_one{{1.2, 0.5, 0.4, 0.3, 0.2, 0.1, -1.5, 0.05}};
  detail::ContractionEstimate slow(8, TwoPhaseMap::n);
  map.feed(slow, above_one, 40);
  ASSERT_TRUE(slow.rate().has_value());
  EXPECT_NEAR(*slow.rate(), 0.5, 1e-6) << "1.2 and -1.5 are left out";

  // sr-arap's rotations are no exact fit: every value counts, |-1.5| clamped.
  detail::ContractionEstimate inexact(8, TwoPhaseMap::n, Policy::Recent, /*exact_local_fit=*/false);
  map.feed(inexact, negative, 40);
  ASSERT_TRUE(inexact.rate().has_value());
  EXPECT_EQ(*inexact.rate(), detail::ContractionEstimate::kMaxRate);

  // Windows whose values are all left out are no estimates: no rate, rather than a rate of 0.
  const Eigen::VectorXd all_negative{{-0.9, -0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2}};
  detail::ContractionEstimate none(8, TwoPhaseMap::n);
  map.feed(none, all_negative, 40);
  EXPECT_FALSE(none.rate().has_value());
}

// A warm start's estimate (Policy::Warm) reads the last 10 estimates above the hint: a slow phase is
// forgotten once 10 fast estimates follow, however long it lasted, but never below the hint.
TEST(ContractionEstimate, AWarmStartReadsTheLastTenAboveItsHint) {
  TwoPhaseMap map;
  detail::ContractionEstimate estimate(8, TwoPhaseMap::n, detail::ContractionEstimate::Policy::Warm);
  estimate.set_floor(0.7);
  ASSERT_TRUE(estimate.rate().has_value()) << "the hint is a rate from the first iteration";
  EXPECT_NEAR(*estimate.rate(), 0.7, 1e-12);
  const Eigen::VectorXd &slow = map.slow, &fast = map.fast;
  auto feed = [&](const Eigen::VectorXd& eigenvalues, int count) { map.feed(estimate, eigenvalues, count); };
  feed(slow, 40);
  EXPECT_NEAR(*estimate.rate(), 0.99, 1e-6);
  feed(fast, 20);  // as in TheLaterHalfKeeps...: the Recent policy still says 0.99 here
  EXPECT_NEAR(*estimate.rate(), 0.7, 1e-6) << "the fast phase's 0.5 stays under the hint";
  EXPECT_NEAR(*estimate.recent_rate(), 0.7, 1e-6);
}

TEST(RateProbe, TheStartVectorIsFixedAndUnit) {
  const Eigen::VectorXd a = detail::probe_start(1000), b = detail::probe_start(1000);
  EXPECT_EQ(a, b);
  EXPECT_NEAR(a.norm(), 1.0, 1e-12);
  EXPECT_GT(a.maxCoeff(), 0.0);
  EXPECT_LT(a.minCoeff(), 0.0);
}

// A 21 x 21 flat sheet, border fixed, the centre disk pulled up: arap-sr stops within a few windows.
struct SmallSheet : solver_testing::PulledSheet {
  SmallSheet() : PulledSheet(solver_testing::pulled_sheet(20, 0.08, 0.0)) {}
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
  EXPECT_LE(r.probe_evaluations, 41);  // one probe of at most 40 steps
  ASSERT_TRUE(r.contraction_rate.has_value());
  ASSERT_TRUE(r.estimate_rate.has_value());
  // A floor under both rates: the probe's rate with its distance to 1 halved (Arnoldi approaches it from
  // below).
  EXPECT_GE(*r.contraction_rate, std::min(1.0 - 0.5 * (1.0 - *r.probe_rate), 0.999));
  EXPECT_GT(*r.contraction_rate, *r.probe_rate);
  EXPECT_GE(*r.estimate_rate, *r.contraction_rate);
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

// A warm start reads its own last 10 Ritz values above a settled hint, so a rate counts as settled only once
// the probe (or the probe's window) has passed: a cold solve's progress reports before its probe carry
// unsettled rates, and so does a cold solve cancelled before then. A warm start from a settled hint is
// settled from its first iteration; one from an unsettled hint is not.
TEST(SolverRateProbe, AColdSolvesRateIsSettledOnlyOnceProbed) {
  const SmallSheet s;
  DeformOptions options;
  options.method = Method::ArapSR;
  Deformer deformer(s.mesh, s.roi, options);
  int with_rate = 0, settled = 0;
  const DeformResult cold =
      deformer.solve(deformer.push_pull_targets(0.9 * s.d), [&](const IterationReport& r) {
        if (r.probe_step > 0) return true;
        with_rate += r.contraction_rate.has_value() ? 1 : 0;
        settled += r.rate_settled ? 1 : 0;
        return true;
      });
  ASSERT_TRUE(cold.converged);
  ASSERT_TRUE(cold.probe_rate.has_value()) << "the sheet no longer stops early: pick a problem that does";
  EXPECT_GT(with_rate, 0) << "the rate is known before the probe";
  EXPECT_EQ(settled, 0) << "every report came before the probe";
  ASSERT_TRUE(cold.contraction_rate.has_value());
  EXPECT_TRUE(cold.rate_settled) << "probed";

  auto warm_from = [&](bool hint_settled, int& reports, int& settled_reports) {
    ConstraintTargets targets = deformer.push_pull_targets(s.d);
    targets.initial_guess = cold.V;
    targets.rate_hint = cold.contraction_rate;
    targets.rate_hint_settled = hint_settled;
    return deformer.solve(targets, [&](const IterationReport& r) {
      ++reports;
      settled_reports += r.rate_settled ? 1 : 0;
      return true;
    });
  };
  int reports = 0, settled_reports = 0;
  const DeformResult warm = warm_from(true, reports, settled_reports);
  EXPECT_GT(reports, 0);
  EXPECT_EQ(settled_reports, reports);
  EXPECT_TRUE(warm.rate_settled);
  reports = settled_reports = 0;
  const DeformResult unsettled = warm_from(false, reports, settled_reports);
  ASSERT_LE(unsettled.iterations, 32);
  EXPECT_EQ(settled_reports, 0);
  EXPECT_FALSE(unsettled.rate_settled);

  // The cold solve again, superseded at the iteration where it met its tolerance, before its probe: its rate
  // is known there (it made the error estimate) but not settled.
  const DeformResult cancelled =
      deformer.solve(deformer.push_pull_targets(0.9 * s.d),
                     [&](const IterationReport& r) { return r.iteration < cold.iterations; });
  ASSERT_TRUE(cancelled.cancelled);
  EXPECT_EQ(cancelled.iterations, cold.iterations);
  EXPECT_TRUE(cancelled.contraction_rate.has_value());
  EXPECT_FALSE(cancelled.rate_settled);
}

TEST(SolverRateProbe, TheProgressCallbackCanCancelDuringTheProbe) {
  const SmallSheet s;
  DeformOptions options;
  options.method = Method::ArapSR;
  int last_iteration = 0, probe_steps = 0;
  options.progress = [&](const IterationReport& report) {
    if (report.probe_step == 0) {
      last_iteration = report.iteration;
      return true;
    }
    EXPECT_EQ(report.iteration, last_iteration);  // the iteration the probe checks
    EXPECT_EQ(report.probe_step, probe_steps + 1);
    ++probe_steps;
    return report.probe_step < 3;
  };
  const DeformResult r = deform(*s.mesh, s.roi, s.d, options);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.stop_reason, StopReason::Cancelled);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(probe_steps, 3);
  EXPECT_EQ(r.iterations, last_iteration);
  EXPECT_FALSE(r.probe_rate.has_value());
  EXPECT_TRUE(r.V.allFinite());
}

}  // namespace
}  // namespace pushpull::deform
