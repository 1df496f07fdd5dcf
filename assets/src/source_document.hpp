// The parsed glTF JSON of a loaded file, kept (immutable) so the GLB writer can carry nodes,
// materials, textures and extensions through unchanged.
#pragma once

#include "pushpull/assets/model.hpp"

#include <nlohmann/json.hpp>

namespace pushpull::assets {

struct SourceDocument {
  nlohmann::json json;
};

}  // namespace pushpull::assets
