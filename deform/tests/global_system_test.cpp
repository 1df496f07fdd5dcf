// GlobalSystem (deform/src/global_system.hpp): both factorization backends solve the same systems, the
// split triangular solves give the same bits on one or two threads, refactorization reuses the analysis,
// and a singular or indefinite block raises FactorizationError with the same message on either backend.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>
#include <string>
#include <vector>

#include "../src/global_system.hpp"
#include "../src/helper_thread.hpp"

namespace pushpull::deform::detail {
namespace {

using Backend = GlobalSystem::Backend;

// A grid Laplacian (side x side, 4-neighbours, random positive edge weights) plus a small diagonal shift:
// symmetric positive definite, both triangles stored. The last `constrained` vertices are the constrained
// block. Large enough that the split solve has two real subtrees.
Eigen::SparseMatrix<double> grid_matrix(int side, unsigned seed) {
  const int n = side * side;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  std::vector<Eigen::Triplet<double>> t;
  auto edge = [&](int a, int b) {
    const double w = weight(random);
    t.emplace_back(a, a, w), t.emplace_back(b, b, w), t.emplace_back(a, b, -w), t.emplace_back(b, a, -w);
  };
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const int v = y * side + x;
      if (x + 1 < side) edge(v, v + 1);
      if (y + 1 < side) edge(v, v + side);
      t.emplace_back(v, v, 1e-3);
    }
  }
  Eigen::SparseMatrix<double> Q(n, n);
  Q.setFromTriplets(t.begin(), t.end());
  Q.makeCompressed();
  return Q;
}

Eigen::Matrix3Xd random_columns(int columns, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::Matrix3Xd B(3, columns);
  for (Eigen::Index k = 0; k < B.size(); ++k) B.data()[k] = value(random);
  return B;
}

// Q_ff Y = B for the first n_free rows and columns, through a dense solve (reference).
Eigen::Matrix3Xd dense_solve(const Eigen::SparseMatrix<double>& Q, int n_free, const Eigen::Matrix3Xd& B) {
  const Eigen::MatrixXd dense = Eigen::MatrixXd(Q).topLeftCorner(n_free, n_free);
  return dense.ldlt().solve(B.transpose()).transpose();
}

class GlobalSystemBackends : public ::testing::TestWithParam<Backend> {};

TEST_P(GlobalSystemBackends, SolvesLikeADenseFactorization) {
  const Eigen::SparseMatrix<double> Q = grid_matrix(24, 1);
  const int n_free = static_cast<int>(Q.cols()) - 30;
  GlobalSystem system;
  system.analyze(Q, n_free, GetParam());
  system.factorize(Q);
  const Eigen::Matrix3Xd B = random_columns(n_free, 2);
  Eigen::Matrix3Xd Y = B;
  system.solve_in_place(Y);
  const Eigen::Matrix3Xd expected = dense_solve(Q, n_free, B);
  EXPECT_LT((Y - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
}

TEST_P(GlobalSystemBackends, TwoThreadsAndRepeatsGiveTheSameBits) {
  const Eigen::SparseMatrix<double> Q = grid_matrix(40, 3);
  const int n_free = static_cast<int>(Q.cols()) - 40;
  const Eigen::Matrix3Xd B = random_columns(n_free, 4);
  GlobalSystem first, second;
  first.analyze(Q, n_free, GetParam());
  first.factorize(Q);
  second.analyze(Q, n_free, GetParam());
  second.factorize(Q);
  Eigen::Matrix3Xd one = B, two = B, again = B;
  first.solve_in_place(one);
  HelperThread threads;
  first.solve_in_place(two, &threads);
  second.solve_in_place(again);
  EXPECT_TRUE(one == two) << "the split solve depends on the thread count";
  EXPECT_TRUE(one == again) << "two analyses of the same matrix gave different factors";
}

TEST_P(GlobalSystemBackends, RefactorizationFollowsNewValues) {
  const Eigen::SparseMatrix<double> Q = grid_matrix(20, 5);
  Eigen::SparseMatrix<double> scaled = Q;
  for (Eigen::Index k = 0; k < scaled.nonZeros(); ++k) scaled.valuePtr()[k] *= 3.0;
  const int n_free = static_cast<int>(Q.cols()) - 20;
  GlobalSystem system;
  system.analyze(Q, n_free, GetParam());
  system.factorize(Q);
  system.factorize(scaled);  // same pattern: the analysis is reused
  const Eigen::Matrix3Xd B = random_columns(n_free, 6);
  Eigen::Matrix3Xd Y = B;
  system.solve_in_place(Y);
  const Eigen::Matrix3Xd expected = dense_solve(scaled, n_free, B);
  EXPECT_LT((Y - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
}

TEST_P(GlobalSystemBackends, IndefiniteBlockNamesThePivot) {
  Eigen::SparseMatrix<double> Q(3, 3);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}, {1, 1, 1.0},  {0, 1, 2.0}, {1, 0, 2.0},
                                           {2, 2, 1.0}, {0, 2, -1.0}, {2, 0, -1.0}};
  Q.setFromTriplets(t.begin(), t.end());
  GlobalSystem system;
  system.analyze(Q, 2, GetParam());
  try {
    system.factorize(Q);
    FAIL() << "an indefinite matrix was factored";
  } catch (const FactorizationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("the global matrix (2 free vertices) is singular or indefinite (pivot"),
              std::string::npos)
        << message;
  }
}

TEST_P(GlobalSystemBackends, ZeroBlockIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> Q(3, 3);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 0.0}, {1, 1, 0.0}, {0, 1, 0.0}, {1, 0, 0.0}, {2, 2, 1.0}};
  Q.setFromTriplets(t.begin(), t.end());
  GlobalSystem system;
  system.analyze(Q, 2, GetParam());
  EXPECT_THROW(system.factorize(Q), FactorizationError);
}

TEST_P(GlobalSystemBackends, AnalyzeLikeSolvesAnotherMatrixOfThePatternAndLeavesTheFirst) {
  const Eigen::SparseMatrix<double> Q = grid_matrix(24, 1);
  const Eigen::SparseMatrix<double> other = grid_matrix(24, 5);  // same pattern, other weights
  const int n_free = static_cast<int>(Q.cols()) - 30;
  GlobalSystem first;
  first.analyze(Q, n_free, GetParam());
  first.factorize(Q);
  GlobalSystem second;
  second.analyze_like(first);
  EXPECT_EQ(second.free_count(), n_free);
  second.factorize(other);
  const Eigen::Matrix3Xd B = random_columns(n_free, 6);
  Eigen::Matrix3Xd Y = B, Y_first = B;
  second.solve_in_place(Y);
  first.solve_in_place(Y_first);
  const Eigen::Matrix3Xd expected = dense_solve(other, n_free, B);
  const Eigen::Matrix3Xd expected_first = dense_solve(Q, n_free, B);
  EXPECT_LT((Y - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
  EXPECT_LT((Y_first - expected_first).cwiseAbs().maxCoeff(), 1e-9 * expected_first.cwiseAbs().maxCoeff());
  // The constrained block holds the new matrix's values too.
  const Eigen::MatrixXd other_fc = Eigen::MatrixXd(other).topRightCorner(n_free, 30);
  const Eigen::Matrix3Xd X_c = random_columns(30, 7);
  const Eigen::Matrix3Xd expected_rhs = -(X_c * other_fc.transpose());
  EXPECT_LT((second.constrained_rhs(X_c) - expected_rhs).cwiseAbs().maxCoeff(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Backends, GlobalSystemBackends,
                         ::testing::Values(Backend::Eigen, Backend::Cholmod, Backend::Automatic),
                         [](const ::testing::TestParamInfo<Backend>& info) {
                           return info.param == Backend::Eigen     ? std::string("Eigen")
                                  : info.param == Backend::Cholmod ? std::string("Cholmod")
                                                                   : std::string("Automatic");
                         });

TEST(GlobalSystemBackends, CholmodAndEigenAgree) {
  if (!GlobalSystem::cholmod_available()) GTEST_SKIP() << "built without CHOLMOD";
  const Eigen::SparseMatrix<double> Q = grid_matrix(30, 7);
  const int n_free = static_cast<int>(Q.cols()) - 30;
  GlobalSystem eigen, cholmod;
  eigen.analyze(Q, n_free, Backend::Eigen);
  eigen.factorize(Q);
  cholmod.analyze(Q, n_free, Backend::Cholmod);
  cholmod.factorize(Q);
  const Eigen::Matrix3Xd B = random_columns(n_free, 8);
  Eigen::Matrix3Xd a = B, b = B;
  eigen.solve_in_place(a);
  cholmod.solve_in_place(b);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9 * a.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace pushpull::deform::detail
