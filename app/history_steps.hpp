// Undo and redo as the review loops ask for them, and the history as the HUD and the window title tell it:
// an undo with nothing to undo (or a redo with nothing to redo) is not sent, so the loop can say so instead
// of doing nothing silently (and the recording does not keep a step that did nothing).
//
// Thread-safety: plain functions over deform::Service (whose calls are thread-safe); call from the loop.
#pragma once

#include "pushpull/deform/service.hpp"

#include <cstddef>
#include <string>

namespace pushpull::app {

enum class HistoryStep { Undo, Redo };

// Sends the step unless the service is idle and its history has nothing in that direction (then returns
// false). While the service is busy a commit may still be on its way into the history, so the step is sent
// (the service ignores it at an end of the history).
bool request_history_step(deform::Service& service, HistoryStep step);
// Sends the step as it is (a replay's recorded decision).
void send_history_step(deform::Service& service, HistoryStep step);

// "nothing to undo" / "nothing to redo".
[[nodiscard]] const char* nothing_to(HistoryStep step);

// The committed edits the history holds and how many of them are undone now.
struct EditCounts {
  std::size_t edits = 0;
  std::size_t undone = 0;
};
[[nodiscard]] EditCounts edit_counts(const deform::Service& service);
// "no edits", "1 edit", "3 edits, 1 undone".
[[nodiscard]] std::string edit_counts_text(EditCounts counts);

}  // namespace pushpull::app
