// One line of text for deform::DeformationMetrics::reversals_by_band (the curvature-sign reversals counted
// again under raised flat bands, metrics.hpp), shared by `pushpull deform`'s console, the replay report and
// the replay comparison page, e.g. "44 of 912 (radius < 13.8 m); 25 of 870 (radius < 4.38 m); ...".
// Radii are printed in metres at life size: the band's radius_below (model units) times metres_per_unit.
// Empty for an empty list. Thread-safety: a free function without state.
#pragma once

#include <string>
#include <vector>

#include "pushpull/deform/metrics.hpp"

namespace pushpull::app {

[[nodiscard]] std::string describe_band_reversals(const std::vector<deform::BandReversals>& bands,
                                                  double metres_per_unit);

}  // namespace pushpull::app
