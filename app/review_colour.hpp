// What the review's surface colours show, and the names the windows, the menu and the command line use.
// Thread-safety: pure functions.
#pragma once

namespace pushpull::app {

enum class ReviewColour { Material, Displacement, CurvatureSign };

// Material -> displacement -> curvature sign -> material (a key cycles through them).
[[nodiscard]] ReviewColour next_colour(ReviewColour c);
// "material", "displacement", "curvature-sign" (as --colour spells them).
[[nodiscard]] const char* colour_name(ReviewColour c);

}  // namespace pushpull::app
