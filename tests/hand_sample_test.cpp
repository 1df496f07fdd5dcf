#include "hand_sample.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace {

using pushpull::app::HandSample;
using pushpull::app::hold_untracked;
using pushpull::app::pointer_pose;

pushpull::xr::HandInput hand(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, bool tracked,
                             float trigger = 1.0f) {
  pushpull::xr::HandInput in;
  in.T_stage_aim = pointer_pose(origin, direction);
  in.aim_position_tracked = tracked;
  in.trigger = trigger;
  return in;
}

// Out of the cameras' view the runtime's position is a drifting guess: the origin stays where the hand was
// last tracked, while the direction (from the controller's own gyroscopes) and the trigger follow the hand.
TEST(HandSample, AnUntrackedPositionIsHeldAndTheDirectionFollows) {
  std::optional<HandSample> last;
  const HandSample seen = hold_untracked(hand({0.1, 1.0, -0.5}, {0, 0, -1}, true), last);
  ASSERT_TRUE(seen.tracked);
  const HandSample guessed = hold_untracked(hand({0.4, 1.2, -0.1}, {1, 0, -1}, false, 0.25f), last);
  EXPECT_TRUE(guessed.tracked);
  EXPECT_LT((guessed.origin_stage - seen.origin_stage).norm(), 1e-12);
  EXPECT_LT((guessed.direction_stage - Eigen::Vector3d(1, 0, -1).normalized()).norm(), 1e-6);
  EXPECT_FLOAT_EQ(guessed.trigger, 0.25f);
  // Tracked again: the live pose, which becomes the one held next time.
  const HandSample back = hold_untracked(hand({0.3, 1.1, -0.2}, {0, -1, 0}, true), last);
  EXPECT_LT((back.origin_stage - Eigen::Vector3d(0.3, 1.1, -0.2)).norm(), 1e-6);
  ASSERT_TRUE(last.has_value());
  EXPECT_LT((last->origin_stage - back.origin_stage).norm(), 1e-12);
}

// A guess before any tracked pose is no ray at all; a pose that is not located is none either.
TEST(HandSample, NoTrackedPoseYetOrNoPoseIsNotTracked) {
  std::optional<HandSample> last;
  EXPECT_FALSE(hold_untracked(hand({0, 1, 0}, {0, 0, -1}, false), last).tracked);
  EXPECT_FALSE(last.has_value());
  pushpull::xr::HandInput lost;
  lost.trigger = 1.0f;
  const HandSample none = hold_untracked(lost, last);
  EXPECT_FALSE(none.tracked);
  EXPECT_FLOAT_EQ(none.trigger, 1.0f);
}

}  // namespace
