// The cold solve's smooth start (deform/src/smooth_start.hpp, DeformOptions::smooth_start_min_free): the
// spread solves the uniform biharmonic system (checked against a dense solve written out here), a rigid
// translation spreads as itself, and an asan Deformer that starts from it begins at a lower energy and still
// ends at the minimiser (checked against a reference solved to 1e-9 |d|); warm starts, small regions under
// the default threshold, methods other than asan and the paper's setting start from rest.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <set>
#include <utility>
#include <vector>

#include "../src/global_system.hpp"
#include "../src/smooth_start.hpp"
#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

// A (side + 1)^2 grid with both diagonals' patterns of a triangulated sheet, numbered interior first
// (free) and border last (constrained): the pattern of a global matrix Q in the solver's local numbering,
// with Q's values a positive definite weighted Laplacian (1 + the edge's index mod 3 per edge).
struct LocalGrid {
  Eigen::SparseMatrix<double> Q;
  int n_free = 0;
  std::vector<std::pair<int, int>> edges;  // local numbering
};

LocalGrid local_grid(int side) {
  const int count = (side + 1) * (side + 1);
  std::vector<int> local(static_cast<std::size_t>(count));
  LocalGrid g;
  auto border = [&](int i, int j) { return i == 0 || j == 0 || i == side || j == side; };
  int next = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j <= side; ++j)
      for (int i = 0; i <= side; ++i)
        if (border(i, j) == (pass == 1)) local[static_cast<std::size_t>(j * (side + 1) + i)] = next++;
  for (int j = 0; j <= side; ++j)
    for (int i = 0; i <= side; ++i)
      if (!border(i, j)) ++g.n_free;
  std::set<std::pair<int, int>> edges;
  auto add = [&](int a, int b) { edges.insert({std::min(a, b), std::max(a, b)}); };
  for (int j = 0; j <= side; ++j) {
    for (int i = 0; i <= side; ++i) {
      const int v = local[static_cast<std::size_t>(j * (side + 1) + i)];
      if (i < side) add(v, local[static_cast<std::size_t>(j * (side + 1) + i + 1)]);
      if (j < side) add(v, local[static_cast<std::size_t>((j + 1) * (side + 1) + i)]);
      if (i < side && j < side) add(v, local[static_cast<std::size_t>((j + 1) * (side + 1) + i + 1)]);
    }
  }
  std::vector<Eigen::Triplet<double>> t;
  int k = 0;
  for (const auto& [a, b] : edges) {
    const double w = 1.0 + (k++ % 3);
    t.emplace_back(a, a, w), t.emplace_back(b, b, w), t.emplace_back(a, b, -w), t.emplace_back(b, a, -w);
    g.edges.emplace_back(a, b);
  }
  g.Q.resize(count, count);
  g.Q.setFromTriplets(t.begin(), t.end());
  g.Q.makeCompressed();
  return g;
}

// The uniform biharmonic spread written out: L = D - A of the edges, minimise |L [D_f; D_c]|^2 over D_f.
Eigen::Matrix3Xd dense_biharmonic(const LocalGrid& g, const Eigen::Matrix3Xd& D_c) {
  const int n = static_cast<int>(g.Q.cols());
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
  for (const auto& [a, b] : g.edges) {
    L(a, a) += 1.0, L(b, b) += 1.0, L(a, b) -= 1.0, L(b, a) -= 1.0;
  }
  const Eigen::MatrixXd Lf = L.leftCols(g.n_free), Lc = L.rightCols(n - g.n_free);
  // Least squares: Lf D_f^T = -Lc D_c^T.
  const Eigen::MatrixXd rhs = -Lc * D_c.transpose();
  return (Lf.transpose() * Lf).ldlt().solve(Lf.transpose() * rhs).transpose();
}

// A LocalGrid's global system, analysed and factored, and the smooth start prepared from it.
struct PreparedGrid {
  LocalGrid g;
  detail::GlobalSystem system;
  detail::SmoothStart start;
  explicit PreparedGrid(int side) : g(local_grid(side)) {
    system.analyze(g.Q, g.n_free);
    system.factorize(g.Q);
    start.prepare(g.Q, system);
  }
};

TEST(SmoothStart, SolvesTheUniformBiharmonicSystem) {
  const PreparedGrid grid(14);
  const LocalGrid& g = grid.g;
  const detail::GlobalSystem& system = grid.system;
  const detail::SmoothStart& start = grid.start;
  ASSERT_TRUE(start.prepared());
  const int n_c = static_cast<int>(g.Q.cols()) - g.n_free;
  Eigen::Matrix3Xd D_c = Eigen::Matrix3Xd::Zero(3, n_c);
  for (int k = 0; k < n_c; k += 7) D_c.col(k) = Eigen::Vector3d(0.1 * k, -0.05, 0.3);  // a lumpy border
  const detail::SmoothStart::Spread spread = start.displacement(D_c);
  EXPECT_TRUE(spread.converged);
  ASSERT_EQ(spread.free.cols(), g.n_free);
  const Eigen::Matrix3Xd expected = dense_biharmonic(g, D_c);
  EXPECT_LT((spread.free - expected).cwiseAbs().maxCoeff(), 1e-2 * D_c.cwiseAbs().maxCoeff());
  // The harmonic spread (the CG's start) is farther: the iterations did something.
  detail::GlobalSystem uniform;  // harmonic with uniform weights, for comparison
  Eigen::SparseMatrix<double> L = g.Q;
  for (int j = 0; j < L.outerSize(); ++j) {
    double degree = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if (it.row() != j) it.valueRef() = -1.0, degree += 1.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
      if (it.row() == j) it.valueRef() = degree;
  }
  uniform.analyze(L, g.n_free);
  uniform.factorize(L);
  Eigen::Matrix3Xd harmonic = uniform.constrained_rhs(D_c);
  uniform.solve_in_place(harmonic);
  EXPECT_GT((harmonic - expected).cwiseAbs().maxCoeff(),
            5.0 * (spread.free - expected).cwiseAbs().maxCoeff());
  // The system whose analysis was reused still solves its own matrix.
  Eigen::Matrix3Xd y = Eigen::Matrix3Xd::Ones(3, g.n_free);
  system.solve_in_place(y);
  const Eigen::MatrixXd Qff = Eigen::MatrixXd(g.Q).topLeftCorner(g.n_free, g.n_free);
  EXPECT_LT((Qff * y.transpose() - Eigen::MatrixXd::Ones(g.n_free, 3)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(SmoothStart, ARigidTranslationSpreadsAsItself) {
  const PreparedGrid grid(12);
  const LocalGrid& g = grid.g;
  const detail::SmoothStart& start = grid.start;
  const int n_c = static_cast<int>(g.Q.cols()) - g.n_free;
  const Eigen::Vector3d t(0.25, -1.5, 3.0);
  const detail::SmoothStart::Spread spread = start.displacement(t.replicate(1, n_c));
  EXPECT_TRUE(spread.converged);
  EXPECT_LT((spread.free - t.replicate(1, g.n_free)).cwiseAbs().maxCoeff(), 1e-9);
}

struct Sheet : solver_testing::PulledSheet {
  Sheet() : PulledSheet(solver_testing::pulled_sheet(40, 0.1, 0.05)) {}
};

TEST(SmoothStartSolve, AsanStartsLowerAndEndsAtTheMinimiser) {
  const Sheet s;
  DeformOptions options;  // asan
  const Eigen::MatrixXd reference = solver_testing::asan_reference_from_rest(s);

  DeformOptions smooth_options;
  smooth_options.smooth_start_min_free = 0;
  Deformer smooth_deformer(s.mesh, s.roi, smooth_options);
  const DeformResult smooth = smooth_deformer.solve(s.d);
  DeformOptions rest_options;
  rest_options.smooth_start_min_free = -1;
  const DeformResult rest = Deformer(s.mesh, s.roi, rest_options).solve(s.d);
  EXPECT_TRUE(smooth.smooth_start);
  EXPECT_FALSE(rest.smooth_start);
  ASSERT_TRUE(smooth.converged);
  std::printf("initial energy %.4e smooth, %.4e rest; %d / %d iterations\n", smooth.initial_energy,
              rest.initial_energy, smooth.iterations, rest.iterations);
  EXPECT_LT(smooth.initial_energy, 0.1 * rest.initial_energy);
  const double error = (smooth.V - reference).rowwise().norm().maxCoeff() / s.d.norm();
  EXPECT_LE(error, 2.0 * options.tolerance);
  ASSERT_TRUE(smooth.error_estimate.has_value());
  EXPECT_LE(error, 2.0 * *smooth.error_estimate);

  // A second cold solve reuses the prepared start; a warm start does not use it.
  const DeformResult again = smooth_deformer.solve(s.d);
  EXPECT_TRUE(again.smooth_start);
  EXPECT_EQ(again.iterations, smooth.iterations);
  ConstraintTargets warm = smooth_deformer.push_pull_targets(1.01 * s.d);
  warm.initial_guess = smooth.V;
  warm.rate_hint = smooth.contraction_rate;
  EXPECT_FALSE(smooth_deformer.solve(warm).smooth_start);
}

TEST(SmoothStartSolve, SmallRegionsOtherMethodsAndThePaperSettingStartFromRest) {
  const Sheet s;
  DeformOptions options;  // asan
  ASSERT_GT(options.smooth_start_min_free, static_cast<int>(s.roi.free.size()));
  EXPECT_FALSE(Deformer(s.mesh, s.roi, options).solve(s.d).smooth_start);
  options.smooth_start_min_free = 0;
  EXPECT_FALSE(Deformer(s.mesh, s.roi, paper_iterations(options)).solve(s.d).smooth_start);
  options.method = Method::ArapSR;  // its estimate ran optimistic from the smooth start (deformer.hpp)
  EXPECT_FALSE(Deformer(s.mesh, s.roi, options).solve(s.d).smooth_start);
  options.smooth_start_min_free = -2;
  EXPECT_THROW(Deformer(s.mesh, s.roi, options), std::invalid_argument);
}

}  // namespace
}  // namespace pushpull::deform
