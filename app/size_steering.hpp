// The handle and region sizes steered between drags by the right thumbstick (headset; the desktop's keys set
// them at once, kSizeStep a press, as "sizes" records a replay sets again).
//
// Stick: up/down grows/shrinks the handle, right/left the region, x2 per second at full deflection; a dead
// zone of 0.2 keeps a resting thumb from drifting them. The sizes are logged ({"event":"sizes"}) and printed
// once the stick is back at rest. Thread-safety: the loop's thread.
#pragma once

#include <optional>

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

// The sizes as they now are: an {"event":"sizes"} line in the log and, with print, a line on stdout.
void report_sizes(const ReviewInteraction& interaction, EventLog& log, const LifeSize& life, bool print);

// One press of the desktop's size keys scales a radius by this.
inline constexpr double kSizeStep = 1.25;

// A trackpad (htc/vive) reads a position whenever a thumb rests on it, so it does not steer the sizes: a
// click on its rim steps them, kSizeStep a click (top/bottom: the handle up/down, right/left: the region),
// and a click within 0.5 of its centre is the menu button. (x, y): the trackpad where it was clicked, -1..1.
// Returns the factors {handle, region}, or nullopt for a centre click.
struct SizeFactors {
  double handle = 1.0, region = 1.0;
};
[[nodiscard]] std::optional<SizeFactors> trackpad_click_step(float x, float y);

// The interaction profile whose thumbstick action is a trackpad.
inline constexpr const char* kTrackpadProfile = "/interaction_profiles/htc/vive_controller";

}  // namespace pushpull::app
