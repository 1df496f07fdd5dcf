// The batched rotation step: one step per lane as closest_rotation takes it, the same lanes finished, and a
// batch step followed by closest_rotation for the unfinished lanes reaches the SVD's optimum.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "../src/rotation.hpp"
#include "../src/rotation_batch.hpp"

namespace pushpull::deform::detail {
namespace {

void put(RotationLanes& lanes, int l, const Eigen::Matrix3d& A, const Eigen::Quaterniond& q) {
  for (int k = 0; k < 9; ++k) lanes.a[k][l] = A(k / 3, k % 3);
  for (int k = 0; k < 4; ++k) lanes.q[k][l] = q.coeffs()[k];
}

Eigen::Matrix3d rotation_of(const RotationLanes& lanes, int l) {
  Eigen::Matrix3d R;
  for (int k = 0; k < 9; ++k) R(k / 3, k % 3) = lanes.r[k][l];
  return R;
}

Eigen::Quaterniond quaternion_of(const RotationLanes& lanes, int l) {
  return Eigen::Quaterniond(lanes.q[3][l], lanes.q[0][l], lanes.q[1][l], lanes.q[2][l]);
}

TEST(SolverRotationBatch, StepThenContinuationMatchesSvd) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  int finished_lanes = 0;
  for (int batch = 0; batch < 500; ++batch) {
    RotationLanes lanes;
    Eigen::Matrix3d A[kRotationLanes];
    for (int l = 0; l < kRotationLanes; ++l) {
      // Near-rotations with a nearby warm start (the solver's state once warm), and every 4th lane a
      // random matrix from a random start (cold, saddles and reflections included).
      Eigen::Quaterniond truth(normal(rng), normal(rng), normal(rng), normal(rng));
      truth.normalize();
      Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();
      for (int i = 0; i < 9; ++i) stretch(i) += 0.2 * normal(rng);
      const bool cold = l % 4 == 3;
      if (cold) {
        for (int i = 0; i < 9; ++i) A[l](i) = normal(rng);
      } else {
        A[l] = truth.toRotationMatrix() * (stretch + stretch.transpose()) * 0.5;
      }
      Eigen::Quaterniond start =
          truth *
          Eigen::Quaterniond(1.0, 1e-3 * normal(rng), 1e-3 * normal(rng), 1e-3 * normal(rng)).normalized();
      if (cold) start = Eigen::Quaterniond::UnitRandom();
      put(lanes, l, A[l], start);
    }
    const std::uint32_t finished = closest_rotation_step(lanes, 1e-2);
    for (int l = 0; l < kRotationLanes; ++l) {
      Eigen::Quaterniond q = quaternion_of(lanes, l);
      EXPECT_NEAR(q.norm(), 1.0, 1e-12);
      Eigen::Matrix3d R = rotation_of(lanes, l);
      EXPECT_LT((R - q.toRotationMatrix()).cwiseAbs().maxCoeff(), 1e-12);
      if ((finished >> l) & 1u) {
        ++finished_lanes;
      } else {
        R = closest_rotation(A[l], q, 19, 1e-2);
      }
      const Eigen::Matrix3d reference = closest_rotation_svd(A[l]);
      EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
      // A finished lane has taken a Newton step shorter than 1e-2 rad: its value is within ~(1e-2)^2 of
      // the optimum, relative to A.
      EXPECT_NEAR((R.array() * A[l].array()).sum(), (reference.array() * A[l].array()).sum(),
                  2e-4 * A[l].norm())
          << "batch " << batch << " lane " << l;
    }
  }
  // The warm lanes (3 of 4) finish in one step.
  EXPECT_GE(finished_lanes, 500 * kRotationLanes * 3 / 4 * 9 / 10);
}

TEST(SolverRotationBatch, OneStepIsTheScalarStep) {
  // closest_rotation with max_steps = 1 and an accept_step that any step meets returns after its first
  // (Newton) step: the same step, so the two quaternions agree to rounding.
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  RotationLanes lanes;
  Eigen::Matrix3d A[kRotationLanes];
  Eigen::Quaterniond start[kRotationLanes];
  for (int l = 0; l < kRotationLanes; ++l) {
    start[l] = Eigen::Quaterniond::UnitRandom();
    A[l] = start[l].toRotationMatrix() * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    A[l] += 0.05 * Eigen::Matrix3d::Random();
    put(lanes, l, A[l], start[l]);
  }
  (void)closest_rotation_step(lanes, 1e-2);
  for (int l = 0; l < kRotationLanes; ++l) {
    Eigen::Quaterniond q = start[l];
    (void)closest_rotation(A[l], q, 1, 10.0);
    const Eigen::Quaterniond batch = quaternion_of(lanes, l);
    EXPECT_LT(std::min((batch.coeffs() - q.coeffs()).norm(), (batch.coeffs() + q.coeffs()).norm()), 1e-12)
        << l;
  }
}

TEST(SolverRotationBatch, EveryLaneGivesTheSameBits) {
  // The same cluster in all 8 lanes: each lane computes it alone, in the same order (a replay's hashes rest
  // on it), whichever vector width the clone uses.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 200; ++k) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = normal(rng);
    const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
    RotationLanes lanes;
    for (int l = 0; l < kRotationLanes; ++l) put(lanes, l, A, q);
    const std::uint32_t finished = closest_rotation_step(lanes, 1e-2);
    EXPECT_TRUE(finished == 0u || finished == (1u << kRotationLanes) - 1u) << k;
    for (int l = 1; l < kRotationLanes; ++l) {
      for (int i = 0; i < 4; ++i) EXPECT_EQ(lanes.q[i][l], lanes.q[i][0]) << k << " lane " << l;
      for (int i = 0; i < 9; ++i) EXPECT_EQ(lanes.r[i][l], lanes.r[i][0]) << k << " lane " << l;
    }
  }
}

TEST(SolverRotationBatch, DegenerateLanesKeepTheirWarmStart) {
  RotationLanes lanes;
  const Eigen::Quaterniond warm(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  for (int l = 0; l < kRotationLanes; ++l) put(lanes, l, Eigen::Matrix3d::Identity(), warm);
  put(lanes, 0, Eigen::Matrix3d::Zero(), warm);
  Eigen::Matrix3d nan_matrix = Eigen::Matrix3d::Identity();
  nan_matrix(1, 2) = std::numeric_limits<double>::quiet_NaN();
  put(lanes, 1, nan_matrix, warm);
  Eigen::Matrix3d infinite = Eigen::Matrix3d::Identity();
  infinite(0, 0) = std::numeric_limits<double>::infinity();
  put(lanes, 2, infinite, warm);
  put(lanes, 3, 1e-300 * Eigen::Matrix3d::Identity(), Eigen::Quaterniond::Identity());  // tiny but valid
  const std::uint32_t finished = closest_rotation_step(lanes, 1e-2);
  for (int l = 0; l < 3; ++l) {
    EXPECT_TRUE((finished >> l) & 1u) << l;
    EXPECT_LT((quaternion_of(lanes, l).coeffs() - warm.coeffs()).norm(), 1e-15) << l;
    EXPECT_TRUE(rotation_of(lanes, l).allFinite()) << l;
  }
  // Scale-free: the identity start is already the maximum for a tiny multiple of I.
  EXPECT_TRUE((finished >> 3) & 1u);
  EXPECT_LT((rotation_of(lanes, 3) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // Half a turn away from the maximum the gradient vanishes too, but it is no maximum: not finished (the
  // caller goes on alone and ends at the SVD).
  RotationLanes saddle;
  for (int l = 0; l < kRotationLanes; ++l)
    put(saddle, l, Eigen::Matrix3d::Identity(), Eigen::Quaterniond::Identity());
  put(saddle, 0, Eigen::Matrix3d::Identity(), Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0));
  EXPECT_FALSE(closest_rotation_step(saddle, 1e-2) & 1u);
}

}  // namespace
}  // namespace pushpull::deform::detail
