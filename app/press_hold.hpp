// A press held back by the headset loop: the trigger went down while a commit, undo or redo was still being
// solved, so the press would have hit a surface about to be replaced. The loop lets it through once the
// deformation service is idle, without ever waiting for it in a frame. The recording keeps every hold ("press
// held" records) so that a replay holds the same press over the same frames, whatever its solver's timing.
// Times are the recording's clock (s; frame n at n / rate). Thread-safety: a plain value.
#pragma once

namespace pushpull::app {

struct PressHold {
  double from = 0.0;      // the frame at which the trigger was first held back
  double until = 0.0;     // the frame at which the hold ended
  bool admitted = false;  // true: the press went through at `until`; false: the trigger was let go first
};

}  // namespace pushpull::app
