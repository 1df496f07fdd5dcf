// How the readouts (by the hand, by the cursor, the window's HUD and title) state the solver's progress on a
// drag from the newest snapshot. Thread-safety: pure functions.
#pragma once

#include "pushpull/deform/service.hpp"

namespace pushpull::app {

// Whether `s` is a preview of a drag's request. While dragging, the newest snapshot is the previous
// push/pull's commit (or an undo's state) until the first preview of this drag lands: its iterations and
// "converged" are not this drag's.
[[nodiscard]] bool is_drag_preview(const deform::Snapshot& s);

// The solver's state in a snapshot, as the readouts say it while dragging: "waiting" until this drag's first
// preview, then "solving" until it is final, then "converged" or "not converged".
[[nodiscard]] const char* solver_state(const deform::Snapshot& s);

// The iterations the readouts show while dragging: the preview's, 0 before this drag's first preview.
[[nodiscard]] int drag_iterations(const deform::Snapshot& s);

}  // namespace pushpull::app
