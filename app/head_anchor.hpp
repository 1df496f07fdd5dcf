// The model stands in front of the reviewer, wherever they stand on the stage.
//
// place_on_stage (stage_placement.hpp) places the model for a reviewer at the stage origin looking down -Z.
// On a real runtime the STAGE origin is the middle of the play area and the reviewer may stand anywhere in
// it, facing any way. So the headset loop anchors the placement to the head at the first frame it is located:
// the placement is turned about the vertical by the head's yaw and moved to the head's floor position. A head
// within 1 cm of the origin and 0.01 rad of facing -Z keeps the placement as it is (so a reviewer who starts
// where the origin is sees exactly the placement place_on_stage made).
//
// Units: metres and radians, stage frame (+Y up). Thread-safety: plain values and pure functions.
#pragma once

#include "stage_placement.hpp"

#include <Eigen/Core>

#include <optional>
#include <utility>

namespace pushpull::app {

struct HeadAnchor {
  double time = 0.0;        // the recording time of the frame it was taken at (s)
  double x = 0.0, z = 0.0;  // the head's floor position (stage metres)
  double yaw = 0.0;         // the head's heading about +Y (radians; 0: looking down -Z, +pi/2: down -X)
  // The floor's height (stage metres): 0 where the stage space stands on the floor, as the spec's STAGE
  // does; otherwise (a head located outside kFloorLevelHeads above the origin: a runtime whose STAGE is its
  // tracking origin, as Monado's is on drivers without a floor) kAssumedEyeHeight below the head.
  double floor_y = 0.0;
};

// Heights of a located head (stage metres, above the origin) that say the stage space stands on the floor:
// a reviewer kneeling to look under a sill to one standing on a step. Outside them the floor is taken
// kAssumedEyeHeight below the head (the LOCAL space fallback's guess too, xr::Session).
inline constexpr double kFloorLevelHeadMin = 0.3, kFloorLevelHeadMax = 2.5, kAssumedEyeHeight = 1.6;

// The anchor of a head at `position` looking along `forward` (stage; forward need not be unit): the heading
// of forward's horizontal part, 0 when the head looks within about 6 degrees of straight up or down; the
// floor's height (HeadAnchor::floor_y); zero (no move) within 1 cm and 0.01 rad of the origin's pose, with
// the floor at 0.
[[nodiscard]] HeadAnchor anchor_at_head(double time, const Eigen::Vector3d& position,
                                        const Eigen::Vector3d& forward);

// T_stage_model moved to the anchor: turned about +Y by yaw, then moved by (x, floor_y, z). A zero anchor
// returns `at_origin` unchanged (bit for bit).
[[nodiscard]] StagePlacement anchored(const StagePlacement& at_origin, const HeadAnchor& anchor);

// When the headset loop anchors, once per review: live, at the first frame whose head position is located (a
// headset tracked in orientation only never anchors); in a replay, at the recorded anchor's frame, or never
// when the recording has none.
class AnchorSchedule {
 public:
  // recorded: unset = live; set = replay, with the recorded anchor or none.
  explicit AnchorSchedule(std::optional<std::optional<HeadAnchor>> recorded)
      : recorded_(std::move(recorded)) {}

  // The frame at recording time t (s; half_frame: half its period). Live: head_position (stage) and
  // head_forward (the heading between the eyes) when the head's position is located this frame, else empty.
  // Returns the anchor to apply in this frame, at most once.
  [[nodiscard]] std::optional<HeadAnchor> take(double t, double half_frame,
                                               const std::optional<Eigen::Vector3d>& head_position,
                                               const Eigen::Vector3d& head_forward);
  [[nodiscard]] bool done() const { return done_; }

 private:
  std::optional<std::optional<HeadAnchor>> recorded_;
  bool done_ = false;
};

}  // namespace pushpull::app
