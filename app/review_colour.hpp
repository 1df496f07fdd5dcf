// What the review's surface colours show, and the names the windows, the menu and the command line use.
// Thread-safety: pure functions.
#pragma once

#include <optional>
#include <string_view>

namespace pushpull::app {

enum class ReviewColour { Material, Displacement, CurvatureSign };

// Material -> displacement -> curvature sign -> material (a key cycles through them).
[[nodiscard]] ReviewColour next_colour(ReviewColour c);
// "material", "displacement", "curvature-sign" (as --colour spells them).
[[nodiscard]] const char* colour_name(ReviewColour c);
// The colour map colour_name() names; nullopt for any other name.
[[nodiscard]] std::optional<ReviewColour> parse_colour(std::string_view name);

}  // namespace pushpull::app
