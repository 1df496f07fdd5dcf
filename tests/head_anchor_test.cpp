// app/head_anchor: the placement made for a reviewer at the stage origin looking down -Z, moved to a head
// elsewhere on the stage.
#include "head_anchor.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using pushpull::app::anchor_at_head;
using pushpull::app::anchored;
using pushpull::app::HeadAnchor;

// A 2 x 1 x 1 box placed as place_on_stage places it: on the floor, its nearest point 0.6 m in front.
pushpull::app::StagePlacement box_placement() {
  Eigen::MatrixXd V(8, 3);
  for (int i = 0; i < 8; ++i) V.row(i) << (i & 1 ? 1.0 : -1.0), (i & 2 ? 1.0 : 0.0), (i & 4 ? 0.5 : -0.5);
  return pushpull::app::place_on_stage(V, {});
}

TEST(HeadAnchor, AHeadAtTheOriginLookingDownMinusZKeepsThePlacementBitForBit) {
  const auto placement = box_placement();
  const HeadAnchor a = anchor_at_head(0.0, {0.004, 1.7, -0.003}, {0.005, -0.4, -1.0});
  EXPECT_EQ(a.x, 0.0);
  EXPECT_EQ(a.z, 0.0);
  EXPECT_EQ(a.yaw, 0.0);
  EXPECT_EQ(anchored(placement, a).T_stage_model, placement.T_stage_model);
}

TEST(HeadAnchor, TheModelIsAsFarInFrontOfAMovedAndTurnedHeadAsOfTheOrigin) {
  const auto placement = box_placement();
  // Looking down -X (turned 90 degrees left), tilted down, from (2, 1.6, -1).
  const HeadAnchor a = anchor_at_head(0.5, {2.0, 1.6, -1.0}, {-0.8, -0.6, 0.0});
  EXPECT_DOUBLE_EQ(a.time, 0.5);
  EXPECT_NEAR(a.yaw, M_PI / 2, 1e-12);
  const auto moved = anchored(placement, a);
  // Every model point: its height is kept, and its offset from the head, seen along the head's heading, is
  // the offset from the origin seen along -Z.
  const Eigen::Vector3d heading(-1.0, 0.0, 0.0), left(0.0, 0.0, 1.0);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1, 1, 0.5), Eigen::Vector3d(-1, 0, -0.5)}) {
    const Eigen::Vector3d at_origin = placement.to_stage_point(p), here = moved.to_stage_point(p);
    const Eigen::Vector3d offset = here - Eigen::Vector3d(2.0, 0.0, -1.0);
    EXPECT_NEAR(here.y(), at_origin.y(), 1e-12);
    EXPECT_NEAR(offset.dot(heading), -at_origin.z(), 1e-12);
    EXPECT_NEAR(offset.dot(left), -at_origin.x(), 1e-12);
    EXPECT_TRUE(moved.to_model_point(here).isApprox(p, 1e-12));
  }
}

TEST(HeadAnchor, AHeadLookingStraightDownOrNotFiniteKeepsItsHeading) {
  EXPECT_EQ(anchor_at_head(0.0, {1.0, 1.6, 0.0}, {0.01, -1.0, 0.0}).yaw, 0.0);
  EXPECT_DOUBLE_EQ(anchor_at_head(0.0, {1.0, 1.6, 0.0}, {0.01, -1.0, 0.0}).x, 1.0);
  const HeadAnchor bad = anchor_at_head(0.0, {NAN, 1.6, 0.0}, {0.0, 0.0, -1.0});
  EXPECT_EQ(bad.x, 0.0);
  EXPECT_EQ(bad.z, 0.0);
  EXPECT_EQ(bad.yaw, 0.0);
}

// A stage space at the tracking origin (the head at its height, not 1.6 m above it): the model's floor is
// taken 1.6 m below the head; heads of a kneeling or standing reviewer keep the stage's floor.
TEST(HeadAnchor, AStageNotAtFloorLevelPutsTheFloorBelowTheHead) {
  const auto placement = box_placement();
  const HeadAnchor at_origin = anchor_at_head(0.0, {0.0, 0.02, 0.0}, {0.0, -0.3, -1.0});
  EXPECT_NEAR(at_origin.floor_y, 0.02 - 1.6, 1e-12);
  EXPECT_EQ(at_origin.x, 0.0);
  const auto moved = anchored(placement, at_origin);
  const Eigen::Vector3d corner(1, 0, 0.5);
  EXPECT_NEAR(moved.to_stage_point(corner).y(), placement.to_stage_point(corner).y() + 0.02 - 1.6, 1e-12);
  EXPECT_NEAR(anchor_at_head(0.0, {0.5, 3.1, 0.0}, {0.0, 0.0, -1.0}).floor_y, 1.5, 1e-12);
  for (const double y : {0.3, 0.5, 1.2, 1.7, 2.5})
    EXPECT_EQ(anchor_at_head(0.0, {0.5, y, 0.0}, {0, 0, -1}).floor_y, 0.0);
  EXPECT_EQ(anchor_at_head(0.0, {0.5, NAN, 0.0}, {0, 0, -1}).floor_y, 0.0);  // not finite: no anchor at all
}

TEST(AnchorSchedule, LiveAnchorsOnceAtTheFirstLocatedHead) {
  pushpull::app::AnchorSchedule live(std::nullopt);
  const Eigen::Vector3d forward(-1.0, 0.0, 0.0);
  EXPECT_FALSE(live.take(0.0, 0.01, std::nullopt, forward).has_value());  // orientation only
  EXPECT_FALSE(live.done());
  const auto a = live.take(0.1, 0.01, Eigen::Vector3d(1.0, 1.6, 2.0), forward);
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(a->time, 0.1);
  EXPECT_DOUBLE_EQ(a->x, 1.0);
  EXPECT_NEAR(a->yaw, M_PI / 2, 1e-12);
  EXPECT_TRUE(live.done());
  EXPECT_FALSE(live.take(0.2, 0.01, Eigen::Vector3d(3.0, 1.6, 2.0), forward).has_value());  // once
}

TEST(AnchorSchedule, AReplayAnchorsAtTheRecordedFrameWhateverTheHead) {
  const HeadAnchor recorded{0.5, 0.8, 1.5, 1.0};
  pushpull::app::AnchorSchedule replay{std::optional<HeadAnchor>(recorded)};
  const Eigen::Vector3d forward(0.0, 0.0, -1.0), head(9.0, 1.6, 9.0);
  EXPECT_FALSE(replay.take(0.4, 0.01, head, forward).has_value());
  const auto a = replay.take(0.495, 0.01, std::nullopt, forward);  // within half a frame
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->x, 0.8);
  EXPECT_EQ(a->yaw, 1.0);
  EXPECT_FALSE(replay.take(0.6, 0.01, head, forward).has_value());
  // A recording without an anchor never anchors.
  pushpull::app::AnchorSchedule none{std::optional<HeadAnchor>()};
  EXPECT_FALSE(none.take(0.0, 0.01, head, forward).has_value());
  EXPECT_TRUE(none.done());
}

}  // namespace
