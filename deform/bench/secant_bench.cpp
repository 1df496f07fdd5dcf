// secant_bench: the solver's per-iteration bookkeeping after the map, Anderson acceleration (window 5, from a
// full window, as asan), the contraction estimate (window 8) and the plain step's largest vertex move, two
// ways in the same run:
//   shared   - one SecantHistory (secant_history.hpp) read by both, as the solver does (local_global.cpp);
//   separate - Anderson and the estimate each with a history of its own and the move from its own pass over
//              the vectors: the memory traffic of two histories (the layout before the shared one).
// The map is a fixed linear contraction on 3 n coordinates (rates up to 0.999, coupled pairs for complex Ritz
// values), applied outside the timed part. Times in ms per iteration: the smallest of 7 runs of 60 iterations
// each, after 20 untimed ones. Printed, not a timed test.
//
//   ./build/deform/bench/secant_bench [--quick]     (--quick: 10K vertices only)
#include "../src/anderson.hpp"
#include "../src/error_estimate.hpp"
#include "../src/helper_thread.hpp"
#include "../src/secant_history.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <vector>

namespace {

using pushpull::deform::detail::Anderson;
using pushpull::deform::detail::ContractionEstimate;
using pushpull::deform::detail::HelperThread;
using pushpull::deform::detail::SecantHistory;
using Clock = std::chrono::steady_clock;

constexpr int kAndersonWindow = 5;
constexpr int kRateWindow = 8;
constexpr int kWarmup = 20;
constexpr int kTimed = 60;
constexpr int kRuns = 7;

// G(x) = A x + b: coordinate pairs (2i, 2i+1) rotate by a small angle and scale by a rate in [0.5, 0.999].
struct LinearContraction {
  Eigen::VectorXd rate, angle_cos, angle_sin, b;
  explicit LinearContraction(Eigen::Index dimension)
      : rate(dimension / 2), angle_cos(dimension / 2), angle_sin(dimension / 2), b(dimension) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (Eigen::Index i = 0; i < rate.size(); ++i) {
      rate(i) = 0.5 + 0.499 * std::pow(u(rng), 0.2);
      const double angle = 0.05 * u(rng);
      angle_cos(i) = std::cos(angle);
      angle_sin(i) = std::sin(angle);
    }
    for (Eigen::Index i = 0; i < dimension; ++i) b(i) = u(rng) - 0.5;
  }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
    g = b;
    for (Eigen::Index i = 0; i < rate.size(); ++i) {
      const double p = x(2 * i), q = x(2 * i + 1);
      g(2 * i) += rate(i) * (angle_cos(i) * p - angle_sin(i) * q);
      g(2 * i + 1) += rate(i) * (angle_sin(i) * p + angle_cos(i) * q);
    }
    if (x.size() % 2 != 0) g(x.size() - 1) += 0.5 * x(x.size() - 1);
  }
};

// The largest squared per-vertex norm of g - x (the separate layout's own pass).
double largest_move_squared(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  double largest = 0.0;
  for (Eigen::Index v = 0; v + 2 < x.size(); v += 3)
    largest = std::max(largest, (g.segment<3>(v) - x.segment<3>(v)).squaredNorm());
  return largest;
}

enum class Layout { Shared, Separate };

// Runs kWarmup + kTimed iterations from x = 0; returns the timed part's ms per iteration and the final
// residual norm (the same map and steps in both layouts, so the residuals show they did the same work).
std::pair<double, double> run(const LinearContraction& map, Layout layout, HelperThread* threads) {
  const Eigen::Index dimension = map.b.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(dimension), g(dimension), next(dimension);
  SecantHistory history(kRateWindow, dimension);
  Anderson shared_anderson(kAndersonWindow, kAndersonWindow);
  ContractionEstimate shared_estimate(kRateWindow, dimension);
  Anderson own_anderson(kAndersonWindow, dimension, kAndersonWindow);
  ContractionEstimate own_estimate(kRateWindow, dimension);
  double timed_ms = 0.0;
  double sink = 0.0;
  for (int it = 0; it < kWarmup + kTimed; ++it) {
    map.apply(x, g);
    const auto start = Clock::now();
    if (layout == Layout::Shared) {
      sink += history.add(x, g, threads);
      if (!shared_anderson.step(history, g, next, threads)) next = g;
      shared_estimate.add(history);
    } else {
      sink += largest_move_squared(x, g);
      next = own_anderson.step(x, g, threads);
      own_estimate.add(x, g, threads);
    }
    const auto stop = Clock::now();
    if (it >= kWarmup) timed_ms += std::chrono::duration<double, std::milli>(stop - start).count();
    x.swap(next);
  }
  map.apply(x, g);
  if (!std::isfinite(sink)) std::printf("secant_bench: non-finite move\n");
  return {timed_ms / kTimed, (g - x).norm()};
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::vector<long> sizes = quick ? std::vector<long>{10000} : std::vector<long>{10000, 30000, 100000};
  std::printf(
      "secant_bench: Anderson (window %d, full window) + contraction estimate (window %d) + largest move,\n"
      "per iteration after the map; ms, smallest of %d runs of %d iterations\n\n",
      kAndersonWindow, kRateWindow, kRuns, kTimed);
  std::printf("vertices threads   shared separate  sep/shared   residual (shared, separate)\n");
  HelperThread helper;
  for (long vertices : sizes) {
    const LinearContraction map(3 * vertices);
    for (int thread_count : {1, 2}) {
      HelperThread* threads = thread_count == 2 ? &helper : nullptr;
      double best_shared = 1e300, best_separate = 1e300, residual_shared = 0.0, residual_separate = 0.0;
      for (int r = 0; r < kRuns; ++r) {  // interleaved, so drifts in the machine's load hit both alike
        const auto shared = run(map, Layout::Shared, threads);
        const auto separate = run(map, Layout::Separate, threads);
        best_shared = std::min(best_shared, shared.first);
        best_separate = std::min(best_separate, separate.first);
        residual_shared = shared.second;
        residual_separate = separate.second;
      }
      std::printf("%8ld %7d %8.3f %8.3f %11.2f   %.3e %.3e\n", vertices, thread_count, best_shared,
                  best_separate, best_separate / best_shared, residual_shared, residual_separate);
    }
  }
  return 0;
}
