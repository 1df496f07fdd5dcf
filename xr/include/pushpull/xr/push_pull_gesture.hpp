// pushpull::xr::PushPullGesture: turns controller samples into push/pull events.
//
// The reviewer presses the trigger while the aim ray touches the surface (p0, model space), drags,
// and releases (p1). The grabbed surface point follows the hand rigidly: p1 = p0 + (hand position now
// - hand position at press), so d = p1 - p0 is the hand's travel, in model space.
//
// Units: metres. Frame: model space (the caller applies inverse(T_stage_model) to stage poses).
// The trigger uses hysteresis (press above press_threshold, release below release_threshold) so a
// trembling finger does not start and stop drags. Losing tracking while dragging cancels the drag.
// Thread-safety: none; one instance per hand, fed from the frame loop.
#pragma once

#include <glm/vec3.hpp>

#include <optional>

namespace pushpull::xr {

struct ControllerSample {
  double time_s = 0.0;            // sample time, seconds, monotonic
  float trigger = 0.0F;           // 0 = released, 1 = fully pressed
  bool tracked = true;            // false when the runtime lost the controller pose
  glm::dvec3 hand_position{0.0};  // model space, metres
  std::optional<glm::dvec3> surface_hit;  // aim ray's first hit on the surface, model space
};

enum class GestureEventKind { None, Pressed, Dragged, Released, Cancelled };

struct GestureEvent {
  GestureEventKind kind = GestureEventKind::None;
  glm::dvec3 p0{0.0};            // grabbed surface point (valid unless kind == None)
  glm::dvec3 p1{0.0};            // where the grabbed point is now
  [[nodiscard]] glm::dvec3 displacement() const { return p1 - p0; }
};

struct GestureOptions {
  float press_threshold = 0.75F;
  float release_threshold = 0.25F;
  double min_displacement_m = 1e-4;  // a release closer than this to p0 is a click: Cancelled
};

class PushPullGesture {
 public:
  explicit PushPullGesture(GestureOptions options = {});

  // Feeds one sample; returns what happened at it. Samples must come in time order.
  GestureEvent update(const ControllerSample& sample);

  [[nodiscard]] bool dragging() const { return dragging_; }
  // Whether the trigger is down (pressed past press_threshold and not yet back to release_threshold).
  [[nodiscard]] bool trigger_down() const { return trigger_down_; }
  [[nodiscard]] const GestureOptions& options() const { return options_; }

 private:
  GestureOptions options_;
  bool trigger_down_ = false;
  bool dragging_ = false;
  glm::dvec3 p0_{0.0};
  glm::dvec3 hand_at_press_{0.0};
};

}  // namespace pushpull::xr
