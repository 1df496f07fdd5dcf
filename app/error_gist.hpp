// A solver error's gist for a readout or a HUD line, where the whole message does not fit (it goes to stderr
// once the drag is over). Pure function; thread-safe.
#pragma once

#include <string>

namespace pushpull::app {

// Without the "deformer: " and "<method>: " prefixes, up to its first clause (, ; : or an opening
// parenthesis), at most 48 characters: "deformer: arap-s: the energy went negative, -0.42 (from ..." gives
// "the energy went negative". An empty gist reads "see the terminal".
[[nodiscard]] std::string error_gist(const std::string& error);

}  // namespace pushpull::app
