// pushpull::assets::describe_model: the human-readable summary `pushpull info` prints.
// Thread-safety: pure function.
#pragma once

#include "pushpull/assets/model.hpp"

#include <string>

namespace pushpull::assets {

// Size (file units and life size), counts, components, materials, extensions, what welding did,
// and warnings. Multi-line, ends with a newline.
std::string describe_model(const Model& model);

}  // namespace pushpull::assets
