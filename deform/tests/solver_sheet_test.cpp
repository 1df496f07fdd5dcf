// A 2 x 1 flat sheet (fixed at x = 0) pulled in its plane by 1.0 along x with a narrow handle: ASAN keeps the
// sections across d rigid (no lateral contraction, the paper's nu = 0 and stiff sections, section 4.3) while
// arap-sr lets the sheet neck in.
#include <gtest/gtest.h>

#include "pushpull/deform/deformer.hpp"
#include "solver_test_support.hpp"

namespace pushpull::deform {
namespace {

struct SheetSetup {
  Mesh mesh = solver_testing::sheet(40, 20, 2.0, 1.0);
  RegionOfInterest roi;
  SheetSetup() {
    std::vector<int> handle, fixed;
    for (int v = 0; v < mesh.V.rows(); ++v) {
      if (mesh.V(v, 0) < 1e-9) fixed.push_back(v);
      if (mesh.V(v, 0) > 2.0 - 1e-9 && std::abs(mesh.V(v, 1) - 0.5) < 0.11) handle.push_back(v);
    }
    roi = make_roi(mesh, handle, fixed, {});
  }
  // Width across d (y extent) of the deformed rest column x = x_rest.
  double width_at(const Eigen::MatrixXd& V, double x_rest) const {
    double lo = 1e9, hi = -1e9;
    for (int v = 0; v < mesh.V.rows(); ++v) {
      if (std::abs(mesh.V(v, 0) - x_rest) > 1e-9) continue;
      lo = std::min(lo, V(v, 1));
      hi = std::max(hi, V(v, 1));
    }
    return hi - lo;
  }
};

DeformResult pull(const SheetSetup& s, Method method) {
  DeformOptions options;
  options.method = method;
  options.max_iterations = 300;
  // 1e-4 |d| (0.1 mm on this 1 m pull): asan's plain-step move here levels off near 7e-9 |d| where the
  // energy's changes reach its rounding, Anderson's safeguard decides on noise and the Ritz values with it;
  // 1e-5 then asked the estimate to pass on a rate below 0.9993, which happened (102 iterations) or not (300,
  // the cap) with the last bits of the dot products (secant_history.hpp's summation order).
  options.tolerance = 1e-4;
  options.energy_tolerance = 0;
  options.anderson_window = 5;
  return deform(s.mesh, s.roi, Eigen::Vector3d(1.0, 0.0, 0.0), options);
}

TEST(SolverSheet, AsanShowsNoLateralContraction) {
  const SheetSetup s;
  const DeformResult asan = pull(s, Method::Asan);
  const DeformResult arap = pull(s, Method::ArapSR);
  ASSERT_TRUE(asan.converged);
  ASSERT_TRUE(arap.converged);
  const double asan_mid = s.width_at(asan.V, 1.0), arap_mid = s.width_at(arap.V, 1.0);
  const double asan_near = s.width_at(asan.V, 1.5), arap_near = s.width_at(arap.V, 1.5);
  RecordProperty("asan_width_mid", std::to_string(asan_mid));
  RecordProperty("arap_sr_width_mid", std::to_string(arap_mid));
  std::printf("width at mid-length: asan %.4f arap-sr %.4f; at 3/4: asan %.4f arap-sr %.4f\n", asan_mid,
              arap_mid, asan_near, arap_near);
  // Measured: asan 1.0000 / 1.0000, arap-sr 0.9935 / 0.9691. (Both energies have nu = 0 under a uniform
  // stretch; the necking of arap-sr comes from the narrow handle, which asan's stiff sections resist.)
  EXPECT_NEAR(asan_mid, 1.0, 0.001);
  EXPECT_NEAR(asan_near, 1.0, 0.001);
  EXPECT_LT(arap_mid, asan_mid - 0.004);
  EXPECT_LT(arap_near, asan_near - 0.02);
  // The sheet stays in its plane.
  EXPECT_LT(asan.V.col(2).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace pushpull::deform
