// Where the model sits does not change the solve: the Deformer works relative to the region's centroid
// (deformer_impl.hpp). With the model's own coordinates a region far from the origin lost digits in the
// energy and in asan's stretched copy, and took up to twice the iterations (the bundled bonnet 100 m off: 241
// asan iterations instead of 117).
#include <gtest/gtest.h>

#include <cmath>

#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

// deform_bench's wavy sheet at a test's size, its coordinates rounded to multiples of 2^-20 so that moving it
// by a whole number of metres is exact.
solver_testing::PulledSheet dyadic_sheet() {
  solver_testing::PulledSheet s = solver_testing::pulled_sheet(40, 0.1, 0.05);
  Mesh m = *s.mesh;
  m.V = (m.V * 1048576.0).array().round().matrix() / 1048576.0;
  s.mesh = std::make_shared<const Mesh>(std::move(m));
  s.d = Eigen::Vector3d(0.0, 0.0, 0.125);  // dyadic: rest + d is exact too
  return s;
}

std::shared_ptr<const Mesh> moved(const Mesh& mesh, const Eigen::Vector3d& offset) {
  Mesh m = mesh;
  m.V.rowwise() += offset.transpose();
  return std::make_shared<const Mesh>(std::move(m));
}

class Translation : public ::testing::TestWithParam<Method> {};

TEST_P(Translation, AModelMovedFarFromItsOriginSolvesTheSame) {
  const solver_testing::PulledSheet s = dyadic_sheet();
  DeformOptions options;
  options.method = GetParam();
  const DeformResult here = deform(*s.mesh, s.roi, s.d, options);
  ASSERT_TRUE(here.converged);
  // 1 km and 2 km off along two axes, 512 m up: exact moves, so the centred problem is the same, bit for bit.
  const Eigen::Vector3d offset(1024.0, -2048.0, 512.0);
  const DeformResult there = deform(*moved(*s.mesh, offset), s.roi, s.d, options);
  ASSERT_TRUE(there.converged);
  EXPECT_EQ(there.iterations, here.iterations);
  EXPECT_EQ(there.energy_trace, here.energy_trace);
  const Eigen::MatrixXd back = there.V.rowwise() - offset.transpose();
  EXPECT_LE((back - here.V).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_P(Translation, AnInexactMoveStillSolvesAlikeAndKeepsFixedVerticesExactly) {
  const solver_testing::PulledSheet s = solver_testing::pulled_sheet(40, 0.1, 0.05);
  DeformOptions options;
  options.method = GetParam();
  const DeformResult here = deform(*s.mesh, s.roi, s.d, options);
  const Eigen::Vector3d offset(300.3, 0.7, -123.45);
  const std::shared_ptr<const Mesh> far = moved(*s.mesh, offset);
  const DeformResult there = deform(*far, s.roi, s.d, options);
  ASSERT_TRUE(here.converged);
  ASSERT_TRUE(there.converged);
  // Rounding of the moved coordinates only (about 1e-14 of 300 m): the same minimiser, each solve within the
  // tolerance of it, in about the same number of iterations.
  const Eigen::MatrixXd back = there.V.rowwise() - offset.transpose();
  EXPECT_LE((back - here.V).rowwise().norm().maxCoeff(), 2.0 * options.tolerance * s.d.norm());
  EXPECT_LE(there.iterations, here.iterations + here.iterations / 5);
  // Fixed vertices come back as they were, to the bit; handles at rest + d as computed in model coordinates.
  for (const int v : s.roi.fixed) EXPECT_EQ(there.V.row(v), far->V.row(v)) << "fixed vertex " << v;
  for (const int v : s.roi.handle) {
    const Eigen::RowVector3d target = far->V.row(v) + s.d.transpose();
    EXPECT_EQ(there.V.row(v), target) << "handle vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, Translation, ::testing::Values(Method::Asan, Method::ArapSR),
                         [](const ::testing::TestParamInfo<Method>& info) {
                           return info.param == Method::Asan ? std::string("asan") : std::string("arap_sr");
                         });

}  // namespace
}  // namespace pushpull::deform
