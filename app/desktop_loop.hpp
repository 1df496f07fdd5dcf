// Desktop mode of `pushpull review` (--desktop, or no OpenXR runtime/headset): the window is the workspace.
// Orbit camera around the model on the stage (right drag: turn, scroll: zoom); left click on the surface =
// p0, drag in the view plane (with Shift: along the surface normal at p0), release = p1 (commit); keys:
// U undo, R redo, C colour map, M method of the next drag, Esc cancel the drag in progress (between drags:
// end the review). Same deform::Service, stage placement and
// outputs (--out, --events) as the headset.
// Thread-safety: the calling (main) thread, as GLFW requires.
#pragma once

#include "review_loop.hpp"
#include "review_setup.hpp"

namespace pushpull::app {

void run_desktop(const ReviewCommandOptions& options, const ReviewSetup& setup);

}  // namespace pushpull::app
