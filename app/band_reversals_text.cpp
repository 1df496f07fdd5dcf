#include "band_reversals_text.hpp"

#include <cstdio>

namespace pushpull::app {

std::string describe_band_reversals(const std::vector<deform::BandReversals>& bands, double metres_per_unit) {
  std::string text;
  for (const deform::BandReversals& band : bands) {
    char entry[128];
    std::snprintf(entry, sizeof entry, "%s%zu of %zu (radius < %.3g m)", text.empty() ? "" : "; ",
                  band.reversals, band.compared, band.radius_below * metres_per_unit);
    text += entry;
  }
  return text;
}

}  // namespace pushpull::app
