// Reference spaces, bounds, xrLocateSpace and xrLocateViews, through the loader.
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace sim_test;

namespace {

class SpacesTest : public ::testing::Test {
 protected:
  void SetUp() override { use_simulated_runtime(); }
};

TEST_F(SpacesTest, EnumeratesViewLocalStageAndStageHasBounds) {
  Sim sim;
  sim.create_session();
  uint32_t n = 0;
  ASSERT_EQ(xrEnumerateReferenceSpaces(sim.session, 0, &n, nullptr), XR_SUCCESS);
  std::vector<XrReferenceSpaceType> types(n);
  ASSERT_EQ(xrEnumerateReferenceSpaces(sim.session, n, &n, types.data()), XR_SUCCESS);
  EXPECT_EQ(types,
            (std::vector<XrReferenceSpaceType>{XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                               XR_REFERENCE_SPACE_TYPE_STAGE}));
  XrExtent2Df bounds{};
  EXPECT_EQ(xrGetReferenceSpaceBoundsRect(sim.session, XR_REFERENCE_SPACE_TYPE_STAGE, &bounds), XR_SUCCESS);
  EXPECT_GT(bounds.width, 1.f);
  EXPECT_GT(bounds.height, 1.f);
  EXPECT_EQ(xrGetReferenceSpaceBoundsRect(sim.session, XR_REFERENCE_SPACE_TYPE_LOCAL, &bounds),
            XR_SPACE_BOUNDS_UNAVAILABLE);
  EXPECT_EQ(xrGetReferenceSpaceBoundsRect(sim.session, XR_REFERENCE_SPACE_TYPE_UNBOUNDED_MSFT, &bounds),
            XR_ERROR_REFERENCE_SPACE_UNSUPPORTED);
}

TEST_F(SpacesTest, CreateErrors) {
  Sim sim;
  sim.create_session();
  XrReferenceSpaceCreateInfo ci{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
  ci.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_UNBOUNDED_MSFT;
  ci.poseInReferenceSpace.orientation.w = 1.f;
  XrSpace space = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateReferenceSpace(sim.session, &ci, &space), XR_ERROR_REFERENCE_SPACE_UNSUPPORTED);
  ci.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_STAGE;
  ci.poseInReferenceSpace.orientation.w = 0.5f;  // not a unit quaternion
  EXPECT_EQ(xrCreateReferenceSpace(sim.session, &ci, &space), XR_ERROR_POSE_INVALID);
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION};
  XrSpace stage = sim.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  EXPECT_EQ(xrLocateSpace(stage, stage, 0, &loc), XR_ERROR_TIME_INVALID);
  EXPECT_EQ(xrDestroySpace(stage), XR_SUCCESS);
  EXPECT_EQ(xrLocateSpace(stage, stage, 1, &loc), XR_ERROR_HANDLE_INVALID);
}

TEST_F(SpacesTest, ViewIsTheHeadInStageAndLocalStartsAtTheHead) {
  Sim sim;
  sim.create_session();
  XrSpace view = sim.reference_space(XR_REFERENCE_SPACE_TYPE_VIEW);
  XrSpace local = sim.reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);
  XrSpace stage = sim.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  XrSpaceVelocity velocity{XR_TYPE_SPACE_VELOCITY};
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION, &velocity};
  ASSERT_EQ(xrLocateSpace(view, stage, 1000, &loc), XR_SUCCESS);
  const XrSpaceLocationFlags all =
      XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
      XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
  EXPECT_EQ(loc.locationFlags, all);
  EXPECT_FLOAT_EQ(loc.pose.position.y, 1.6f);
  EXPECT_NE(velocity.velocityFlags, 0u);
  ASSERT_EQ(xrLocateSpace(view, local, 1000, &loc), XR_SUCCESS);
  EXPECT_NEAR(loc.pose.position.y, 0.f, 1e-6);
}

TEST_F(SpacesTest, ViewsAreStereoWithAsymmetricMirroredFovs) {
  Sim sim;
  sim.create_session();
  XrSpace local = sim.reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);
  XrViewLocateInfo li{XR_TYPE_VIEW_LOCATE_INFO};
  li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  li.displayTime = 1000;
  li.space = local;
  XrViewState vs{XR_TYPE_VIEW_STATE};
  std::vector<XrView> views(2, {XR_TYPE_VIEW});
  uint32_t n = 0;
  EXPECT_EQ(xrLocateViews(sim.session, &li, &vs, 1, &n, views.data()), XR_ERROR_SIZE_INSUFFICIENT);
  ASSERT_EQ(xrLocateViews(sim.session, &li, &vs, 2, &n, views.data()), XR_SUCCESS);
  ASSERT_EQ(n, 2u);
  EXPECT_NE(vs.viewStateFlags & XR_VIEW_STATE_POSITION_VALID_BIT, 0u);
  EXPECT_NEAR(views[1].pose.position.x - views[0].pose.position.x, 0.064f, 1e-5);
  EXPECT_NE(views[0].fov.angleLeft, -views[0].fov.angleRight);        // asymmetric
  EXPECT_FLOAT_EQ(views[0].fov.angleLeft, -views[1].fov.angleRight);  // mirrored
  li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO;
  EXPECT_EQ(xrLocateViews(sim.session, &li, &vs, 2, &n, views.data()),
            XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
}

TEST_F(SpacesTest, ScriptedHeadPoseIsInterpolated) {
  setenv("PUSHPULL_XR_SIM_INPUT",
         write_temp_file(
             "head.jsonl",
             "{\"t\": 0.0, \"path\": \"/user/head\", \"pose\": {\"p\": [0, 1.5, 0], \"q\": [0, 0, 0, 1]}}\n"
             "{\"t\": 1.0, \"path\": \"/user/head\", \"pose\": {\"p\": [1, 1.5, 0], \"q\": [0, 0.7071068, "
             "0, 0.7071068]}}\n")
             .c_str(),
         1);
  Sim sim;
  sim.create_session();
  sim.begin_session();
  const XrTime t0 = sim.frame();  // frame 0 is script time 0
  XrSpace view = sim.reference_space(XR_REFERENCE_SPACE_TYPE_VIEW);
  XrSpace stage = sim.reference_space(XR_REFERENCE_SPACE_TYPE_STAGE);
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION};
  ASSERT_EQ(xrLocateSpace(view, stage, t0 + 500000000, &loc), XR_SUCCESS);
  EXPECT_NEAR(loc.pose.position.x, 0.5f, 1e-5);
  EXPECT_NEAR(loc.pose.orientation.y, std::sin(M_PI / 8), 1e-4);  // half of 90 degrees about +Y
  ASSERT_EQ(xrLocateSpace(view, stage, t0 + 3000000000, &loc), XR_SUCCESS);
  EXPECT_NEAR(loc.pose.position.x, 1.f, 1e-5);  // held after the last sample
}

}  // namespace
