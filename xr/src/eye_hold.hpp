// Private: the eye poses of a frame whose views carry an orientation but no position (a 3-DoF headset, or
// positional tracking lost for a while): the head stays where it was last located and each eye turns about
// it with its live orientation, so the eyes keep their distance across the line of sight whichever way the
// head turns (eyes held at their last positions would sit one behind the other after a quarter turn, and
// swap after a half turn: stereo gone, then inside out).
// Frames: stage space, metres. Thread-safety: none (the frame loop's).
#pragma once

#include <openxr/openxr.h>

#include <array>

namespace pushpull::xr::detail {

class EyeHold {
 public:
  // views: the two located eye poses of a frame (left, right), whose orientations are valid. With
  // position_valid they are taken as they are and remembered; without, their positions are replaced by the
  // last head centre plus each eye's last offset turned with the eye's live orientation (before any located
  // frame: a standing reviewer's head at 1.6 m above the stage origin, 64 mm between the eyes).
  void apply(std::array<XrPosef, 2>& views, bool position_valid);

 private:
  XrVector3f head_centre_{0.0f, 1.6f, 0.0f};  // midpoint of the eyes when last located
  // Each eye's offset from the head centre, in that eye's own frame.
  std::array<XrVector3f, 2> eye_offset_{{{-0.032f, 0.0f, 0.0f}, {0.032f, 0.0f, 0.0f}}};
};

}  // namespace pushpull::xr::detail
