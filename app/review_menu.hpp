// The headset's method and colour-map panel: the menu button opens it in front of the reviewer, the thumbstick
// moves the selection (up / down, one row per push), the trigger applies the selected row, the menu button
// closes it. While it is open the trigger does not push or pull and the thumbstick does not resize the handle.
// Knows neither OpenXR nor the renderer: the loop feeds it the right hand's stick and trigger and shows lines().
// Thread-safety: one thread (the frame loop).
#pragma once

#include "review_colour.hpp"

#include "pushpull/deform/method.hpp"

#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {

struct MenuChoice {
  std::optional<deform::Method> method;  // the method of the next push/pulls
  std::optional<ReviewColour> colour;    // the colour map
};

class ReviewMenu {
 public:
  // Opens the panel with the selection on the current method, or closes it.
  void toggle(deform::Method current);
  [[nodiscard]] bool is_open() const { return open_; }
  // One frame while open: stick_y in -1..1 (up is +), trigger 0..1. Returns the row applied this frame, if any.
  MenuChoice update(float stick_y, float trigger);
  // The panel's text for the current method and colour map (marked "*"), and the selected line.
  [[nodiscard]] std::vector<std::string> lines(deform::Method method, ReviewColour colour) const;
  [[nodiscard]] int selected_line() const;
  [[nodiscard]] int selected_row() const { return row_; }

 private:
  bool open_ = false;
  int row_ = 0;               // 0..methods-1: methods, then the colour maps
  bool stick_armed_ = true;   // the stick returned to the centre since its last step
  bool trigger_armed_ = true; // the trigger was released since its last press
};

}  // namespace pushpull::app
