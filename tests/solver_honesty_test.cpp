// Honest "converged" on real models: random pulls (stopping_bench --random-pulls --details) whose asan
// solves stopped far closer to done than they were. On the Cesium milk truck (seed 20261202, pulls 2 and 4)
// they stopped after 21-24 iterations 4.1-4.7x optimistic: their regions are whole parts of the truck that no
// fixed vertex holds, and the slow mode was the part's translation; such a part now starts moved with its
// handle, the minimiser, and takes no iteration (deformer_impl.hpp). On the real car (seed 2027, pull 8)
// after 33 iterations 21.8x, just past the 32 iterations the probe then covered. A slow mode (rate above
// 0.99) hid under the fast ones; the rate probe of the early stop (deform/src/rate_probe.hpp) finds it, and
// the estimate then bounds the true distance to the minimiser. sr-arap on the real car (seed 20261202, pull
// 4) stopped after 574 iterations 4.84x optimistic while its local step ran three fixed Gauss-Seidel sweeps
// over its coupled rotations; sweeps until the rotations settle (deform/src/local_global.cpp) made it honest,
// and its region, too, is a whole part (a patch of the car's tessellation) that now takes no iteration. With
// three sweeps and that start, seeds 20261202, 3333, 777001 and 1111 of `stopping_bench --random-pulls 4
// --method sr-arap` stop at most 1.01x optimistic; the car's nose over 1 m (a held region, stopping_bench's
// fixed problems; 6.83x with three sweeps) is too slow for a test. A late stop of the real car (seed 40, pull
// 1: 102 iterations, past asan's probe window) was 2.49x optimistic; regions of at most 8,000 free vertices
// now probe their first stop wherever it comes.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/surface_point.hpp"

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

const char* const kTruck = "gltf/CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb";
const char* const kCar = "gltf/AsamVehicle/vehicle_example.gltf";

struct RandomPull {
  const char* name;
  const char* model;  // under ../shared/data
  int face;
  double radius;  // the region's (the bench: 30% of the truck's diagonal, 15% of the car's)
  Eigen::Vector3d d;
  std::size_t region;  // vertices, as the bench printed
  pd::Method method = pd::Method::Asan;
  bool probed = true;  // an early stop (the rate probe then runs and must find the slow mode)
  bool whole_part = false;  // a part no fixed vertex holds: exact from its start, no iteration
};

class SolverHonesty : public ::testing::TestWithParam<RandomPull> {};

TEST_P(SolverHonesty, AnEarlyStopOnARealModelIsWithinTwiceItsEstimate) {
  const RandomPull pull = GetParam();
  const fs::path path = fs::path(PUSHPULL_SHARED_DATA) / pull.model;
  if (!fs::exists(path)) GTEST_SKIP() << path << " is missing";
  const pd::Mesh mesh = pushpull::assets::load_model(path).deform_mesh;
  ASSERT_LT(pull.face, mesh.F.rows());
  // As the bench draws it: a handle of 8% of the region's radius around the triangle's centre.
  const double radius = pull.radius;
  const Eigen::Vector3d a = mesh.V.row(mesh.F(pull.face, 0)), b = mesh.V.row(mesh.F(pull.face, 1)),
                        c = mesh.V.row(mesh.F(pull.face, 2));
  const pd::SurfacePoint hit{pull.face, (a + b + c) / 3.0};
  const pd::RegionOfInterest roi =
      pd::build_roi(mesh, pd::surface_handle(mesh, hit, 0.08 * radius), {}, radius);
  ASSERT_EQ(roi.size(), pull.region);

  pd::DeformOptions options;
  options.method = pull.method;
  const pd::DeformResult r = pd::deform(mesh, roi, pull.d, options);
  pd::DeformOptions tight = options;
  tight.tolerance = 1e-9;
  tight.max_iterations = 30000;
  const pd::DeformResult reference = pd::deform(mesh, roi, pull.d, tight);
  ASSERT_TRUE(reference.converged);
  ASSERT_TRUE(r.converged);
  ASSERT_TRUE(r.error_estimate.has_value());
  const double truth = (r.V - reference.V).rowwise().norm().maxCoeff() / pull.d.norm();
  std::printf("%d iterations (+%d probe steps, probed rate %.5f), estimate %.2e, true %.2e\n", r.iterations,
              r.probe_evaluations, r.probe_rate.value_or(-1.0), *r.error_estimate, truth);
  EXPECT_LE(truth, 2.0 * *r.error_estimate);
  EXPECT_LE(truth, 2.0 * options.tolerance);
  if (pull.whole_part) {
    EXPECT_TRUE(roi.fixed.empty());
    EXPECT_EQ(r.iterations, 0);
    EXPECT_LE(truth, 1e-12);
  }
  if (!pull.probed) return;
  ASSERT_TRUE(r.probe_rate.has_value());
  EXPECT_GT(*r.probe_rate, 0.99);  // the slow mode, found
}

INSTANTIATE_TEST_SUITE_P(
    Pulls, SolverHonesty,
    ::testing::Values(RandomPull{"TruckPull2",
                                 kTruck,
                                 2563,
                                 1.8535294631749535,
                                 {0.14502084457206335, 0.046206824242296544, -0.072005061751941352},
                                 194,
                                 pd::Method::Asan,
                                 false,
                                 true},
                      RandomPull{"TruckPull4",
                                 kTruck,
                                 3360,
                                 1.8535294631749535,
                                 {-0.075881001698638859, 0.037153201990019993, -0.050006963759889597},
                                 194,
                                 pd::Method::Asan,
                                 false,
                                 true},
                      RandomPull{"CarPull8Seed2027",
                                 kCar,
                                 13816,
                                 0.65649922479319578,
                                 {-0.027845733323806604, -0.01259096856220744, 0.026088128627551603},
                                 1570},
                      // Seed 40, pull 1: a late stop (102 iterations, past asan's window of 80) that was
                      // 2.49x optimistic unprobed; a region this small now probes any first stop.
                      RandomPull{"CarPull1Seed40LateStop",
                                 kCar,
                                 8518,
                                 0.65649922479319578,
                                 {0.035170394461737531, 0.0032773273994734201, -0.044568588743533873},
                                 1462},
                      RandomPull{"CarPull4SrArap",
                                 kCar,
                                 16369,
                                 0.65649922479319578,
                                 {-0.029470422364786881, -0.020361914914394187, 0.0070431924896602223},
                                 128,
                                 pd::Method::SrArap,
                                 false,
                                 true}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
