// The warnings the readouts add while dragging (by the hand, by the cursor): what the reviewer should know
// about the push/pull under way while there is still time to let go. Lengths in model units (the ratios need
// no unit). Thread-safety: pure functions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pushpull/deform/service.hpp"

namespace pushpull::app {

// A pull over kSteepPull handle radii makes a spike rather than a bulge ("steep: 7x the handle radius").
inline constexpr double kSteepPull = 4.0;
// The surface moving over kOvershoot times its pull: a narrow region swinging like a flap ("the surface moves
// 2.0x the pull").
inline constexpr double kOvershoot = 1.5;

// The lines for a drag of |d| = pull with handles of `handle_radius`, given the newest snapshot: steep, the
// surface moving more than the pull, and a region that is a whole part with no border to hold it (a lamp, a
// windscreen: the part moves as one piece; "the whole part moves: no border holds it") or the handle alone (a
// region too small for the triangles around it: "only the handle moves: no region beyond it").
[[nodiscard]] std::vector<std::string> drag_notes(double pull, double handle_radius,
                                                  const deform::Snapshot& s);

// A push/pull of |d| = pull with handles of `handle_radius` (model units) over kSteepPull handle radii: the
// warning `pushpull deform` prints and a replay writes into the commit's metrics ("steep: |d| is 7x the
// handle radius, a spike rather than a bulge (...)"); none for a gentler one.
[[nodiscard]] std::optional<std::string> steep_pull_warning(double pull, double handle_radius);

// A committed pull longer than the model's longest side (a tracking jump at the release, a drag released off
// the desktop window): the warning, with the way back; none for a shorter one. pull and longest_side in model
// units, scale in metres per model unit (the lengths are said in life-size metres).
[[nodiscard]] std::optional<std::string> long_pull_warning(double pull, double longest_side, double scale);

}  // namespace pushpull::app
