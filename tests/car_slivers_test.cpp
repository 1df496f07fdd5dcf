// The real car (AsamVehicle, see ../shared/data/README.md): its body has sliver triangles whose clamped
// cotangents made a 2 m region's global matrix indefinite ("singular or indefinite", energy -747). With
// mollified weights the nose pull of 100 mm solves with asan and arap-sr, the energy is never negative,
// and arap-s says clearly why it cannot be trusted there.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

const fs::path kCar = fs::path(PUSHPULL_SHARED_DATA) / "gltf" / "AsamVehicle" / "vehicle_example.gltf";

class CarSlivers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!fs::exists(kCar)) return;
    car_ = std::make_shared<const pd::Mesh>(pushpull::assets::load_model(kCar).deform_mesh);
    // The front of the hood (front is +X), as `pushpull deform --handle-at 1.855 0.694 0 --handle-radius
    // 0.05 --roi-radius 2` picks it.
    const Eigen::Vector3d nose(1.855, 0.694, 0.0);
    std::vector<int> handle;
    for (int v = 0; v < car_->V.rows(); ++v) {
      if ((car_->V.row(v).transpose() - nose).norm() <= 0.05) handle.push_back(v);
    }
    roi_ = pd::build_roi(*car_, handle, {}, 2.0);
  }
  void SetUp() override {
    if (!car_) GTEST_SKIP() << kCar << " is missing";
    ASSERT_FALSE(roi_.handle.empty());
    ASSERT_FALSE(roi_.fixed.empty());
  }
  static pd::DeformResult pull(pd::Method method, std::unique_ptr<pd::Deformer>& deformer) {
    pd::DeformOptions options;
    options.method = method;
    deformer = std::make_unique<pd::Deformer>(car_, roi_, options);
    return deformer->solve(kPull);
  }
  static inline std::shared_ptr<const pd::Mesh> car_;
  static inline pd::RegionOfInterest roi_;
  static inline const Eigen::Vector3d kPull{0.1, 0.0, 0.0};
};

TEST_F(CarSlivers, NosePullOverTwoMetresSolvesWithNonNegativeEnergy) {
  for (pd::Method method : {pd::Method::Asan, pd::Method::ArapSR}) {
    SCOPED_TRACE(std::string(pd::method_name(method)));
    std::unique_ptr<pd::Deformer> deformer;
    pd::DeformResult r;
    ASSERT_NO_THROW(r = pull(method, deformer));
    ASSERT_TRUE(r.V.allFinite());
    EXPECT_TRUE(r.converged) << pd::stop_reason_name(r.stop_reason);
    const double tolerance = 1e-12 * r.initial_energy;
    EXPECT_GE(r.initial_energy, 0.0);
    for (double e : r.energy_trace) EXPECT_GE(e, -tolerance);
    EXPECT_GE(deformer->energy(r.V), -tolerance);
    // The handle moved by d and nothing moved farther.
    const double largest = (r.V - car_->V).rowwise().norm().maxCoeff();
    EXPECT_NEAR(largest, kPull.norm(), 1e-3 * kPull.norm());
  }
}

TEST_F(CarSlivers, ArapSSaysWhyItFailsAndWhatToTry) {
  std::unique_ptr<pd::Deformer> deformer;
  try {
    const pd::DeformResult r = pull(pd::Method::ArapS, deformer);
    // If arap-s ever solves here, its result must at least be finite and non-negative.
    ASSERT_TRUE(r.V.allFinite());
    EXPECT_GE(r.energy_trace.back(), 0.0);
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("arap-s"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(roi_.size()) + " vertices"), std::string::npos) << what;
    EXPECT_NE(what.find("use arap-sr or asan, or a smaller region"), std::string::npos) << what;
  }
}

}  // namespace
