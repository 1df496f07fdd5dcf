// A reused Deformer: asan recomputes its weights and factorization when the direction of d changes (and
// then gives exactly what a new Deformer gives), and keeps them when only |d| changes or d flips sign.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform {
namespace {

struct ReusedProblem {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
};

ReusedProblem make_setup() {
  ReusedProblem s;
  s.mesh = std::make_shared<const Mesh>(testing::grid(16, 16, 0.0, 1.0, 0.0, 1.0, [](double x, double y) {
    return 0.2 * std::sin(3 * x) * std::cos(2 * y);
  }));
  std::vector<int> handle;
  for (Eigen::Index v = 0; v < s.mesh->V.rows(); ++v)
    if (std::hypot(s.mesh->V(v, 0) - 0.5, s.mesh->V(v, 1) - 0.5) < 0.12)
      handle.push_back(static_cast<int>(v));
  s.roi = build_roi(*s.mesh, handle, {}, 0.4);
  return s;
}

Eigen::MatrixXd fresh(const ReusedProblem& s, const Eigen::Vector3d& d) {
  return Deformer(s.mesh, s.roi, DeformOptions{}).solve(d).V;
}

TEST(SolverReuse, AsanWeightsFollowTheLineOfD) {
  const ReusedProblem s = make_setup();
  Deformer deformer(s.mesh, s.roi, DeformOptions{});  // asan
  const Eigen::Vector3d d1(0.0, 0.0, 0.05), d2(0.04, 0.0, 0.03);

  const DeformResult a = deformer.solve(d1);
  EXPECT_TRUE(a.refactored);
  const double energy_d1_weights = deformer.energy(a.V);

  const DeformResult b = deformer.solve(2.0 * d1);  // same line: same weights, same factorization
  EXPECT_FALSE(b.refactored);
  EXPECT_EQ(deformer.energy(a.V), energy_d1_weights);
  EXPECT_EQ(b.V, fresh(s, 2.0 * d1));

  const DeformResult c = deformer.solve(d2);  // another direction: new weights, new factorization
  EXPECT_TRUE(c.refactored);
  EXPECT_NE(deformer.energy(a.V), energy_d1_weights);  // the same positions cost differently now
  EXPECT_EQ(c.V, fresh(s, d2));                        // exactly what a new Deformer computes

  const DeformResult e = deformer.solve(-d2);  // opposite direction: the stretch depends on d d^T only
  EXPECT_FALSE(e.refactored);
  EXPECT_EQ(e.V, fresh(s, -d2));
}

TEST(SolverReuse, IsotropicMethodsFactorOnce) {
  const ReusedProblem s = make_setup();
  for (Method method : {Method::ArapSR, Method::ArapM, Method::ArapH}) {
    DeformOptions options;
    options.method = method;
    Deformer deformer(s.mesh, s.roi, options);
    EXPECT_TRUE(deformer.solve(Eigen::Vector3d(0.0, 0.0, 0.05)).refactored) << method_name(method);
    EXPECT_FALSE(deformer.solve(Eigen::Vector3d(0.05, 0.0, 0.0)).refactored) << method_name(method);
  }
}

}  // namespace
}  // namespace pushpull::deform
