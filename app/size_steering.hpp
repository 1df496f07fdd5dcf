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

// The frame period (s) the sizes are steered with: that of the recording's whole-Hz clock exactly as xr/sim
// gives a replay of it (XrDuration(1e9 / rate) ns), whatever period the live runtime reported, so a replay
// steers the sizes bit for bit.
[[nodiscard]] double recording_frame_period_s(double rate_hz);

// Desktop keys as stick deflections: each press adds frames_per_press() frames of full deflection along its
// axis (the axes deflect independently; presses against each other cancel), next() gives the stick of each
// frame. One press scales a size by kStep.
class StickPulses {
 public:
  static constexpr double kStep = 1.25;
  // Frames of full deflection for one press at frame period dt (s): round(log2(kStep) / dt).
  [[nodiscard]] static int frames_per_press(double dt);
  // axis 0: x (region), 1: y (handle); direction +1 grows, -1 shrinks.
  void press(int axis, int direction, double dt);
  // The stick for this frame (x, y), counting the frame; held (a drag in progress, when the sizes do not
  // change): centred, and nothing counted, so the pulses go on after the drag.
  [[nodiscard]] std::pair<float, float> next(bool held);

 private:
  int frames_[2] = {0, 0};  // per axis, signed: the direction and the frames of deflection left
};

}  // namespace pushpull::app
