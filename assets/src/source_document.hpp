// The parsed glTF JSON of a loaded file, kept (immutable) so the GLB writer can carry nodes,
// materials, textures and extensions through unchanged.
#pragma once

#include "pushpull/assets/model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace pushpull::assets {

struct SourceDocument {
  nlohmann::json json;
  // The folder the document's relative URIs resolve against (canonical), empty when it had none
  // (a model read from memory without a base folder).
  std::filesystem::path base_dir;
};

}  // namespace pushpull::assets
