#include "pushpull/xr/push_pull_gesture.hpp"

#include <gtest/gtest.h>

namespace pushpull::xr {
namespace {

ControllerSample sample(double t, float trigger, glm::dvec3 hand, std::optional<glm::dvec3> hit = {}) {
  ControllerSample s;
  s.time_s = t;
  s.trigger = trigger;
  s.hand_position = hand;
  s.surface_hit = hit;
  return s;
}

TEST(PushPullGesture, PressDragReleaseGivesHandTravelAsDisplacement) {
  PushPullGesture gesture;
  EXPECT_EQ(gesture.update(sample(0.0, 0.0F, {0, 0, 0}, glm::dvec3{1, 1, 1})).kind, GestureEventKind::None);
  const GestureEvent press = gesture.update(sample(0.1, 0.9F, {0, 0, 0}, glm::dvec3{1, 1, 1}));
  ASSERT_EQ(press.kind, GestureEventKind::Pressed);
  EXPECT_EQ(press.p0, glm::dvec3(1, 1, 1));
  const GestureEvent drag = gesture.update(sample(0.2, 0.5F, {0, 0.1, 0}));
  ASSERT_EQ(drag.kind, GestureEventKind::Dragged);  // 0.5 is above the release threshold
  EXPECT_NEAR(drag.p1.y, 1.1, 1e-12);
  const GestureEvent release = gesture.update(sample(0.3, 0.1F, {0.2, 0.3, 0}));
  ASSERT_EQ(release.kind, GestureEventKind::Released);
  EXPECT_NEAR(release.displacement().x, 0.2, 1e-12);
  EXPECT_NEAR(release.displacement().y, 0.3, 1e-12);
  EXPECT_FALSE(gesture.dragging());
}

TEST(PushPullGesture, PressWithoutSurfaceHitDoesNotGrab) {
  PushPullGesture gesture;
  EXPECT_EQ(gesture.update(sample(0.0, 1.0F, {0, 0, 0})).kind, GestureEventKind::None);
  // Holding the trigger and then sweeping onto the surface must not grab: the press was in the air.
  EXPECT_EQ(gesture.update(sample(0.1, 1.0F, {0, 0, 0}, glm::dvec3{0, 0, 0})).kind, GestureEventKind::None);
  EXPECT_FALSE(gesture.dragging());
}

TEST(PushPullGesture, LostTrackingCancelsAndTinyMoveIsAClick) {
  PushPullGesture gesture;
  gesture.update(sample(0.0, 1.0F, {0, 0, 0}, glm::dvec3{0, 0, 0}));
  ControllerSample lost = sample(0.1, 1.0F, {5, 5, 5});
  lost.tracked = false;
  EXPECT_EQ(gesture.update(lost).kind, GestureEventKind::Cancelled);

  PushPullGesture click;
  click.update(sample(0.0, 1.0F, {0, 0, 0}, glm::dvec3{0, 0, 0}));
  EXPECT_EQ(click.update(sample(0.1, 0.0F, {1e-6, 0, 0})).kind, GestureEventKind::Cancelled);
}

TEST(PushPullGesture, RejectsInvertedThresholds) {
  GestureOptions bad;
  bad.press_threshold = 0.2F;
  bad.release_threshold = 0.8F;
  EXPECT_THROW(PushPullGesture{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace pushpull::xr
