#include "../src/anderson.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <optional>

namespace {

using pushpull::deform::detail::Anderson;

// A linear contraction G(x) = A x + b with rates spread up to 0.99: its fixed point is (I - A)^-1 b.
struct LinearMap {
  Eigen::VectorXd a, b;
  explicit LinearMap(int n) : a(n), b(n) {
    for (int i = 0; i < n; ++i) {
      a(i) = 0.99 * (i + 1) / n;
      b(i) = 1.0 + 0.1 * i;
    }
  }
  Eigen::VectorXd operator()(const Eigen::VectorXd& x) const { return a.cwiseProduct(x) + b; }
  Eigen::VectorXd fixed_point() const { return b.cwiseQuotient(Eigen::VectorXd::Ones(a.size()) - a); }
};

// With min_pairs = window the first `window` steps (and the first `window` after a reset) are plain
// G(x); then it extrapolates. With min_pairs = 1 it extrapolates from the second step on.
TEST(Anderson, ExtrapolatesOnlyOnceTheWindowHoldsMinPairs) {
  const LinearMap G(12);
  for (const int min_pairs : {1, 5}) {
    Anderson anderson(5, 12, min_pairs);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(12);
    for (int round = 0; round < 2; ++round) {
      for (int step = 0; step < 7; ++step) {
        const Eigen::VectorXd g = G(x);
        const Eigen::VectorXd next = anderson.step(x, g);
        const bool plain = next == g;
        // Step k (0-based) has k secant pairs: it may extrapolate once k >= min_pairs.
        EXPECT_EQ(plain, step < min_pairs)
            << "min_pairs " << min_pairs << ", round " << round << ", step " << step;
        x = next;
      }
      anderson.reset();
    }
  }
}

// Both settings still converge, and faster than the plain iteration.
TEST(Anderson, AFullWindowStillAccelerates) {
  const LinearMap G(12);
  const Eigen::VectorXd solution = G.fixed_point();
  auto iterations = [&](int window, int min_pairs) {
    std::optional<Anderson> anderson;
    if (window > 0) anderson.emplace(window, 12, min_pairs);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(12);
    for (int k = 1; k <= 5000; ++k) {
      const Eigen::VectorXd g = G(x);
      if ((g - x).norm() < 1e-10) {
        EXPECT_LT((x - solution).norm(), 1e-6 * solution.norm()) << window << " " << min_pairs;
        return k;
      }
      x = anderson ? anderson->step(x, g) : g;
    }
    return 5000;
  };
  const int plain = iterations(0, 1), first = iterations(5, 1), full = iterations(5, 5);
  EXPECT_LT(plain, 5000);
  EXPECT_LT(first, plain / 4);
  EXPECT_LT(full, plain / 4);
}

}  // namespace
