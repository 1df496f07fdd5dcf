// A "sizes" record of a session recording: the handle and region radii a key set at a frame (model units),
// which a replay sets again at the same frame. Thread-safety: a value.
#pragma once

namespace pushpull::app {

struct SizeChange {
  double time = 0.0;  // the recording's clock (s)
  double handle_radius = 0.0;
  double roi_radius = 0.0;
};

}  // namespace pushpull::app
