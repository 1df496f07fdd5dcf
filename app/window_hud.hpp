// The heads-up display of the supervisor's mirror window and of the desktop window: lines of text pinned to
// the window's top-left corner (WorldLabel::place_top_left) with the method, the drag's |d| in life-size mm,
// the solver's iterations and state, the colour map, the mirror's view mode and the keys. The window title
// carries the same state; the HUD keeps it in view on a full-screen window or a projector. Thread-safety:
// plain functions.
#pragma once

#include "life_size.hpp"
#include "review_interaction.hpp"

#include "pushpull/deform/service.hpp"

#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

// A line the HUD and the readout show for a while ("nothing to undo"), on the loop's clock (seconds).
class TimedNotice {
 public:
  void show(std::string text, double now, double seconds = 2.5) {
    text_ = std::move(text);
    until_ = now + seconds;
  }
  // The text until it expires, then empty.
  [[nodiscard]] std::string text(double now) const { return now < until_ ? text_ : std::string(); }

 private:
  std::string text_;
  double until_ = -1.0;
};

// Shows `text` by `notice` from `now` on and, with print, says it on stdout ("pushpull review: <text>").
void announce(TimedNotice& notice, const std::string& text, double now, bool print);

// Line 1: "asan  |d| 70.7 mm  30 it  converged" while dragging, "asan  solving  12 it" while a commit, undo
// or redo is solved, else "asan  ready  <history>" (history: the edits, edit_counts_text(); a notice in its
// place while it shows), followed just after a commit by its own solve's "(commit: 16 it, converged)"; a
// notice follows the other states' line (a key pressed mid-drag); line 2: "colour: displacement" and, when
// view_mode is not empty, "   view: <view_mode>"; then `keys`, one line each.
[[nodiscard]] std::vector<std::string> window_hud_lines(
    const ReviewInteraction& interaction, const deform::Snapshot& snapshot, const LifeSize& life,
    const std::string& colour, const std::string& view_mode, const std::vector<std::string>& keys,
    const std::string& history, const std::string& notice);

// The window title with the same state: "<name> | asan (dragging) | |d| 70.7 mm | 30 it converged |
// displacement" while dragging (then " | <notice>" while one shows), "<name> | asan | <history or notice> |
// displacement" otherwise, and " | <view_mode>" when it is not empty.
[[nodiscard]] std::string window_title(const std::string& name, deform::Method method, bool dragging,
                                       const deform::Snapshot& snapshot, const LifeSize& life,
                                       const std::string& colour, const std::string& view_mode,
                                       const std::string& history, const std::string& notice);

}  // namespace pushpull::app
