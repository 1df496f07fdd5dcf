#include "region_notes.hpp"

namespace pushpull::app {

std::optional<UnheldRegion> unheld_region(const deform::RegionOfInterest& roi) {
  if (!roi.fixed.empty()) return std::nullopt;
  return roi.whole_parts ? UnheldRegion::WholePart : UnheldRegion::HandleOnly;
}

std::string unheld_region_text(UnheldRegion kind) {
  return kind == UnheldRegion::WholePart
             ? "the whole part moves: the region covers its connected part and no border holds it"
             : "only the handle moves, torn from the surface around it: the region holds no vertex beyond "
               "the handle to give";
}

}  // namespace pushpull::app
