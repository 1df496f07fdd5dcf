// SecantHistory (deform/src/secant_history.hpp): its Gram entries, projections, moves and extrapolations
// against the same quantities computed directly from the recorded vectors, over more pairs than its window
// holds and on vectors longer than one chunk, with and without the helper thread.
#include "../src/secant_history.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pushpull::deform::detail {
namespace {

// A fixed nonlinear map with mixed rates, so that the recorded pairs are not collinear.
Eigen::VectorXd image(const Eigen::VectorXd& x) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i)
    g(i) = 0.9 * std::sin(0.7 * x(i) + 0.01 * static_cast<double>(i)) + 0.05 * x((i + 7) % x.size());
  return g;
}

TEST(SecantHistory, GramEntriesProjectionsAndMovesMatchTheirDefinitions) {
  for (const Eigen::Index n :
       {Eigen::Index{10}, Eigen::Index{3 * 2000 + 2}}) {  // one chunk; several, a partial triple
    constexpr int kWindow = 4;
    SecantHistory history(kWindow, n);
    std::vector<Eigen::VectorXd> xs, gs;
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    for (int step = 0; step < 9; ++step) {
      const Eigen::VectorXd g = image(x);
      xs.push_back(x);
      gs.push_back(g);
      const double move = history.add(x, g);
      const Eigen::VectorXd f = g - x;
      double largest = 0.0;
      for (Eigen::Index i = 0; i < n; i += 3)
        largest = std::max(largest, f.segment(i, std::min<Eigen::Index>(3, n - i)).squaredNorm());
      EXPECT_NEAR(move, largest, 1e-14 * largest) << "n " << n << ", step " << step;
      EXPECT_EQ(history.pairs(), step);
      EXPECT_EQ(history.stored(), std::min(step, kWindow));
      // The k-th newest pair is (f, g) at step - k minus (f, g) at step - k - 1.
      auto dF = [&](int k) {
        const std::size_t a = static_cast<std::size_t>(step - k);
        return Eigen::VectorXd((gs[a] - xs[a]) - (gs[a - 1] - xs[a - 1]));
      };
      auto dG = [&](int k) {
        const std::size_t a = static_cast<std::size_t>(step - k);
        return Eigen::VectorXd(gs[a] - gs[a - 1]);
      };
      for (int a = 0; a < history.stored(); ++a) {
        const int ca = history.column(a);
        const double scale = dF(a).norm() * std::max(f.norm(), dG(a).norm()) + 1e-300;
        EXPECT_NEAR(history.f_on_dF()(ca), dF(a).dot(f), 1e-12 * scale);
        for (int b = 0; b < history.stored(); ++b) {
          const int cb = history.column(b);
          const double s = (dF(a).norm() + dG(a).norm()) * (dF(b).norm() + dG(b).norm());
          EXPECT_NEAR(history.ff()(ca, cb), dF(a).dot(dF(b)), 1e-12 * s);
          EXPECT_NEAR(history.fg()(ca, cb), dF(a).dot(dG(b)), 1e-12 * s);
          EXPECT_NEAR(history.gg()(ca, cb), dG(a).dot(dG(b)), 1e-12 * s);
        }
      }
      if (history.stored() >= 2) {
        const Eigen::Vector2d gamma(0.3, -1.7);
        Eigen::VectorXd out(n);
        ASSERT_TRUE(history.extrapolate(g, gamma, out));
        const Eigen::VectorXd expected = g - gamma(0) * dG(0) - gamma(1) * dG(1);
        EXPECT_LT((out - expected).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + expected.cwiseAbs().maxCoeff()));
      }
      x = 0.5 * (x + g);  // damped, so that consecutive pairs differ
    }
  }
}

TEST(SecantHistory, TheHelperThreadGivesTheSameBits) {
  const Eigen::Index n = 3 * 5000;
  HelperThread helper;
  SecantHistory alone(5, n), split(5, n);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0), out_alone(n), out_split(n);
  for (int step = 0; step < 8; ++step) {
    const Eigen::VectorXd g = image(x);
    EXPECT_EQ(alone.add(x, g), split.add(x, g, &helper));
    EXPECT_EQ(alone.ff(), split.ff());
    EXPECT_EQ(alone.fg(), split.fg());
    EXPECT_EQ(alone.gg(), split.gg());
    EXPECT_EQ(alone.f_on_dF(), split.f_on_dF());
    if (alone.stored() > 0) {
      const Eigen::VectorXd gamma = Eigen::VectorXd::Constant(alone.stored(), 0.25);
      ASSERT_TRUE(alone.extrapolate(g, gamma, out_alone));
      ASSERT_TRUE(split.extrapolate(g, gamma, out_split, &helper));
      EXPECT_EQ(out_alone, out_split);
    }
    x = 0.5 * (x + g);
  }
}

TEST(SecantHistory, ANonFiniteExtrapolationIsSaid) {
  SecantHistory history(2, 6);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6), g = Eigen::VectorXd::Ones(6), out(6);
  (void)history.add(x, g);
  (void)history.add(g, 2.0 * g);
  Eigen::VectorXd gamma(1);
  gamma << std::numeric_limits<double>::infinity();
  EXPECT_FALSE(history.extrapolate(2.0 * g, gamma, out));
}

}  // namespace
}  // namespace pushpull::deform::detail
