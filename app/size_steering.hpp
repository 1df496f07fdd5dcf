// The handle and region sizes steered between drags by the right thumbstick (headset) or by keys that deflect
// it (desktop: [ and ] the handle, - and = the region, each press a recorded deflection of the stick for a
// fixed number of frames, so a replay of the recording steers the sizes bit for bit as the window did).
//
// Stick: up/down grows/shrinks the handle, right/left the region, x2 per second at full deflection; a dead
// zone of 0.2 keeps a resting thumb from drifting them. The sizes are logged ({"event":"sizes"}) and printed
// once the stick is back at rest. Thread-safety: the loop's thread.
#pragma once

#include "life_size.hpp"
#include "review_interaction.hpp"
#include "review_setup.hpp"

namespace pushpull::app {

class SizeSteering {
 public:
  // One frame: the stick (x right, y up, -1..1) over dt seconds (the frame's display period); enabled: false
  // while something else has the stick (the menu panel). Changes nothing while dragging.
  void frame(ReviewInteraction& interaction, float x, float y, double dt, bool enabled, EventLog& log,
             const LifeSize& life, bool print);

 private:
  bool changed_ = false;
};

// Desktop keys as stick deflections: press() starts (or lengthens) a full deflection along one axis, next()
// gives the stick of each frame. One press scales a size by kStep over kFrames frames at dt = 1/90 s.
class StickPulses {
 public:
  static constexpr double kStep = 1.25;
  // Frames of full deflection for one press at frame period dt (s): round(log2(kStep) / dt).
  [[nodiscard]] static int frames_per_press(double dt);
  // axis 0: x (region), 1: y (handle); direction +1 grows, -1 shrinks. A press against a running pulse
  // replaces it.
  void press(int axis, int direction, double dt);
  // The stick for this frame (x, y), counting the frame.
  [[nodiscard]] std::pair<float, float> next();

 private:
  int axis_ = 0, direction_ = 0, frames_left_ = 0;
};

}  // namespace pushpull::app
