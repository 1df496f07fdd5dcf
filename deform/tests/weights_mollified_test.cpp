// Mollified cotangent weights (deform/src/cotangent.hpp): every triangle's stiffness is PSD and bounded,
// well-shaped triangles keep their cotangents, and the solver's factorization errors say what to try.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <string>

#include "../src/cotangent.hpp"
#include "../src/global_system.hpp"
#include "../src/solver_errors.hpp"

namespace pushpull::deform::detail {
namespace {

// The 3 x 3 stiffness of one triangle from its three half cotangents (weight k on the edge opposite corner
// k).
Eigen::Matrix3d element(const Eigen::VectorXd& w, int f) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double x = w(3 * f + k);
    K(i, i) += x, K(j, j) += x, K(i, j) -= x, K(j, i) -= x;
  }
  return K;
}

Eigen::Matrix3Xd triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Eigen::Matrix3Xd P(3, 3);
  P << a, b, c;
  return P;
}

const Eigen::MatrixX3i kOneFace = (Eigen::MatrixX3i(1, 3) << 0, 1, 2).finished();

TEST(WeightsMollified, WellShapedTriangleKeepsItsCotangents) {
  const Eigen::Matrix3Xd P = triangle({0, 0, 0}, {1, 0, 0}, {0.3, 0.8, 0.1});
  const HalfCotangents w = half_cotangents(P, kOneFace, mollification_margin(P, kOneFace));
  EXPECT_EQ(w.added_length, 0.0);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = P.col((k + 1) % 3) - P.col(k), v = P.col((k + 2) % 3) - P.col(k);
    EXPECT_NEAR(w.values(k), 0.5 * u.dot(v) / u.cross(v).norm(), 1e-14) << "corner " << k;
  }
}

TEST(WeightsMollified, NeedlesAndCapsGivePsdBoundedElements) {
  for (double aspect : {1e-3, 1e-6, 1e-9, 1e-12, 0.0}) {
    // Cap: apex almost on the long edge; needle: one edge almost zero; and the two at once.
    const Eigen::Matrix3Xd shapes[] = {
        triangle({0, 0, 0}, {1, 0, 0}, {0.4, aspect, 0}),
        triangle({0, 0, 0}, {1, 0, 0}, {1, aspect, 0}),
        triangle({0, 0, 0}, {1, 0, 0}, {1 - aspect, aspect * aspect, 0}),
    };
    for (const Eigen::Matrix3Xd& P : shapes) {
      const double eps = 1e-4;  // as for a mesh of mean edge 1
      const HalfCotangents w = half_cotangents(P, kOneFace, eps);
      ASSERT_TRUE(w.values.allFinite()) << "aspect " << aspect;
      // cot a cot b + cot b cot c + cot c cot a = 1 for a valid triangle (half cotangents: 1/4).
      const double identity =
          w.values(0) * w.values(1) + w.values(1) * w.values(2) + w.values(2) * w.values(0);
      EXPECT_NEAR(identity, 0.25, 1e-8 * w.values.squaredNorm()) << "aspect " << aspect;
      const Eigen::Vector3d eig =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(element(w.values, 0)).eigenvalues();
      EXPECT_GE(eig(0), -1e-12 * eig(2)) << "aspect " << aspect;
      EXPECT_GT(eig(1), 0.0) << "aspect " << aspect;  // only translations are free
      EXPECT_LE(w.values.cwiseAbs().maxCoeff(), 2.0 / eps) << "aspect " << aspect;
      EXPECT_LE(w.added_length, eps);
    }
  }
}

TEST(WeightsMollified, StretchedHealthyTrianglesAreNotMollified) {
  // ASAN's stretch makes well-shaped triangles thin (mu = 100) but leaves their margins far above eps.
  const Eigen::Matrix3Xd P = triangle({0, 0, 0}, {0.1, 0, 0}, {0.03, 0.09, 0.02});
  const double eps = mollification_margin(P, kOneFace);
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1, 1)}) {
    const HalfCotangents w = half_cotangents(stretch_along(P, d, 100.0), kOneFace, eps);
    EXPECT_EQ(w.added_length, 0.0);
  }
}

TEST(WeightsMollified, FactorizationErrorNamesMethodRegionAndRemedy) {
  // An indefinite 2 x 2 free block: GlobalSystem reports the pivot, the Deformer's message adds the rest.
  Eigen::SparseMatrix<double> Q(3, 3);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}, {1, 1, 1.0},  {0, 1, 2.0}, {1, 0, 2.0},
                                           {2, 2, 1.0}, {0, 2, -1.0}, {2, 0, -1.0}};
  Q.setFromTriplets(t.begin(), t.end());
  GlobalSystem system;
  system.analyze(Q, 2);
  try {
    system.factorize(Q);
    FAIL() << "an indefinite matrix was factored";
  } catch (const FactorizationError& e) {
    const std::string message = factorization_failure_message(Method::ArapS, {1234, 1000, 34, 200}, e.what());
    EXPECT_NE(message.find("arap-s"), std::string::npos) << message;
    EXPECT_NE(message.find("indefinite"), std::string::npos) << message;
    EXPECT_NE(message.find("1234 vertices"), std::string::npos) << message;
    EXPECT_NE(message.find("use arap-sr or asan, or a smaller region (--roi-radius)"), std::string::npos)
        << message;
    const std::string other = factorization_failure_message(Method::Asan, {1234, 1000, 34, 200}, e.what());
    EXPECT_NE(other.find("deformer: asan:"), std::string::npos) << other;
  }
}

}  // namespace
}  // namespace pushpull::deform::detail
