// What a push/pull's region says about the result, in words for a person (deform's warnings, the replay's
// metrics and report): a region no border holds moves as one piece when it covers whole parts (a lamp, a
// windscreen grabbed), and leaves its handle torn from the surface when it is the handle alone.
// Thread-safety: a pure function.
#pragma once

#include "pushpull/deform/roi.hpp"

#include <optional>
#include <string>

namespace pushpull::app {

enum class UnheldRegion { WholePart, HandleOnly };

// Which, or none when a border (a Fixed vertex) holds the region.
[[nodiscard]] std::optional<UnheldRegion> unheld_region(const deform::RegionOfInterest& roi);

// The warning for it, without advice on options: "the whole part moves: ..." / "only the handle moves: ...".
[[nodiscard]] std::string unheld_region_text(UnheldRegion kind);

}  // namespace pushpull::app
