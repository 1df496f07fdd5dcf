// The fast polar decomposition agrees with the SVD reference and always returns a proper rotation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "../src/rotation.hpp"

namespace pushpull::deform::detail {
namespace {

TEST(SolverRotation, MatchesSvdOnRandomMatrices) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 2000; ++k) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = normal(rng);
    if (k % 3 == 0) A.col(2) = 0.3 * A.col(0) - A.col(1);  // rank 2 (flat clusters)
    const Eigen::Matrix3d reference = closest_rotation_svd(A);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    const Eigen::Matrix3d R = closest_rotation(A, q);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
    EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
    // Both maximise R : A; the optimum value must agree even where the maximiser is not unique.
    EXPECT_NEAR((R.array() * A.array()).sum(), (reference.array() * A.array()).sum(), 1e-7 * A.norm()) << k;
  }
}

TEST(SolverRotation, ReflectionIsFixedBySmallestSingularVector) {
  const Eigen::Matrix3d A = Eigen::Vector3d(3.0, 2.0, -1.0).asDiagonal();
  const Eigen::Matrix3d R = closest_rotation_svd(A);
  EXPECT_NEAR((R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  EXPECT_NEAR((closest_rotation(A, q) - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
}

TEST(SolverRotation, ZeroMatrixKeepsWarmStart) {
  Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  const Eigen::Matrix3d R = closest_rotation(Eigen::Matrix3d::Zero(), q);
  EXPECT_TRUE(R.allFinite());
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
}

}  // namespace
}  // namespace pushpull::deform::detail
