#include "../src/eye_hold.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using pushpull::xr::detail::EyeHold;

XrQuaternionf yaw(float radians) {  // about +Y (up)
  return {0.0f, std::sin(radians / 2), 0.0f, std::cos(radians / 2)};
}

XrPosef pose(XrQuaternionf q, XrVector3f p) {
  return {q, p};
}

float distance(const XrVector3f& a, const XrVector3f& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// Located views are passed through untouched.
TEST(EyeHold, LocatedViewsAreKept) {
  EyeHold hold;
  std::array<XrPosef, 2> views{pose(yaw(0.3f), {0.1f, 1.7f, 0.2f}), pose(yaw(0.3f), {0.16f, 1.7f, 0.18f})};
  const auto before = views;
  hold.apply(views, true);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(views[i].position.x, before[i].position.x);
    EXPECT_EQ(views[i].position.z, before[i].position.z);
  }
}

// Positional tracking lost after a located frame, then the head turns a quarter and a half turn: the eyes
// stay 64 mm apart across the line of sight (left eye on the left), about the last head centre.
TEST(EyeHold, WithoutPositionTheEyesTurnAboutTheLastHeadCentre) {
  EyeHold hold;
  std::array<XrPosef, 2> located{pose(yaw(0.0f), {0.968f, 1.7f, 2.0f}),
                                 pose(yaw(0.0f), {1.032f, 1.7f, 2.0f})};
  hold.apply(located, true);
  for (const float turn : {0.0f, float(M_PI / 2), float(M_PI)}) {
    // Positions as a runtime may leave them when they are not valid: anything (here zeros).
    std::array<XrPosef, 2> views{pose(yaw(turn), {0, 0, 0}), pose(yaw(turn), {0, 0, 0})};
    hold.apply(views, false);
    const XrVector3f centre{0.5f * (views[0].position.x + views[1].position.x),
                            0.5f * (views[0].position.y + views[1].position.y),
                            0.5f * (views[0].position.z + views[1].position.z)};
    EXPECT_LT(distance(centre, {1.0f, 1.7f, 2.0f}), 1e-5f) << "turn " << turn;
    EXPECT_NEAR(distance(views[0].position, views[1].position), 0.064f, 1e-5f);
    // The head's right (+X turned by the yaw): right eye minus left eye points along it.
    const float right_x = std::cos(turn), right_z = -std::sin(turn);
    const float along = (views[1].position.x - views[0].position.x) * right_x +
                        (views[1].position.z - views[0].position.z) * right_z;
    EXPECT_NEAR(along, 0.064f, 1e-5f) << "turn " << turn;
  }
}

// Located with the head turned: the offsets are kept in the eyes' own frames, so the same orientation
// without position gives the same eyes back, and a further quarter turn turns them about the head centre.
TEST(EyeHold, OffsetsAreKeptInTheEyesOwnFrames) {
  EyeHold hold;
  const float a = 0.7f;
  const XrVector3f centre{0.3f, 1.65f, -0.4f};
  const XrVector3f right{0.032f * std::cos(a), 0.0f, -0.032f * std::sin(a)};  // +X turned by the yaw
  std::array<XrPosef, 2> located{pose(yaw(a), {centre.x - right.x, centre.y, centre.z - right.z}),
                                 pose(yaw(a), {centre.x + right.x, centre.y, centre.z + right.z})};
  hold.apply(located, true);
  std::array<XrPosef, 2> same{pose(yaw(a), {}), pose(yaw(a), {})};
  hold.apply(same, false);
  for (size_t i = 0; i < 2; ++i) EXPECT_LT(distance(same[i].position, located[i].position), 1e-6f) << i;
  const float b = a + float(M_PI / 2);
  std::array<XrPosef, 2> turned{pose(yaw(b), {}), pose(yaw(b), {})};
  hold.apply(turned, false);
  const XrVector3f right_b{0.032f * std::cos(b), 0.0f, -0.032f * std::sin(b)};
  EXPECT_LT(distance(turned[0].position, {centre.x - right_b.x, centre.y, centre.z - right_b.z}), 1e-6f);
  EXPECT_LT(distance(turned[1].position, {centre.x + right_b.x, centre.y, centre.z + right_b.z}), 1e-6f);
}

// Never located (a 3-DoF headset): a standing reviewer's head 1.6 m above the stage origin.
TEST(EyeHold, NeverLocatedEyesStandAtTheOrigin) {
  EyeHold hold;
  std::array<XrPosef, 2> views{pose(yaw(float(M_PI / 2)), {}), pose(yaw(float(M_PI / 2)), {})};
  hold.apply(views, false);
  EXPECT_NEAR(views[0].position.y, 1.6f, 1e-6f);
  EXPECT_NEAR(views[0].position.z, 0.032f, 1e-6f);  // a quarter turn left: the left eye behind (+Z)
  EXPECT_NEAR(views[1].position.z, -0.032f, 1e-6f);
  EXPECT_NEAR(views[0].position.x, 0.0f, 1e-6f);
}

}  // namespace
