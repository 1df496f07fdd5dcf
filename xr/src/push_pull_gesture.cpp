#include "pushpull/xr/push_pull_gesture.hpp"

#include <glm/geometric.hpp>

#include <stdexcept>

namespace pushpull::xr {

PushPullGesture::PushPullGesture(GestureOptions options) : options_(options) {
  if (!(options_.release_threshold < options_.press_threshold)) {
    throw std::invalid_argument("PushPullGesture: release_threshold must be below press_threshold");
  }
}

GestureEvent PushPullGesture::update(const ControllerSample& sample) {
  const bool was_down = trigger_down_;
  if (!trigger_down_ && sample.trigger >= options_.press_threshold) {
    trigger_down_ = true;
  } else if (trigger_down_ && sample.trigger <= options_.release_threshold) {
    trigger_down_ = false;
  }

  GestureEvent event;
  if (dragging_) {
    event.p0 = p0_;
    if (!sample.tracked) {
      dragging_ = false;
      event.kind = GestureEventKind::Cancelled;
      event.p1 = p0_;
      return event;
    }
    event.p1 = p0_ + (sample.hand_position - hand_at_press_);
    if (trigger_down_) {
      event.kind = GestureEventKind::Dragged;
    } else {
      dragging_ = false;
      const bool moved = glm::length(event.p1 - event.p0) >= options_.min_displacement_m;
      event.kind = moved ? GestureEventKind::Released : GestureEventKind::Cancelled;
    }
    return event;
  }

  // A press only grabs when the aim ray touches the surface at the moment the trigger goes down.
  if (!was_down && trigger_down_ && sample.tracked && sample.surface_hit) {
    dragging_ = true;
    p0_ = *sample.surface_hit;
    hand_at_press_ = sample.hand_position;
    event.kind = GestureEventKind::Pressed;
    event.p0 = p0_;
    event.p1 = p0_;
  }
  return event;
}

}  // namespace pushpull::xr
