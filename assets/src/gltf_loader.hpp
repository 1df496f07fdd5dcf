// glTF 2.0 / GLB loading with tinygltf (with accessor_reader.cpp, the only code that includes tiny_gltf.h).
// Fills a Model's render side (primitives flattened from the default scene with their world
// transforms, materials, textures, samplers, images), its report's format/warnings/extensions,
// and its source document. Welding is done afterwards by load_model.
// Thread-safety: reentrant. Errors throw AssetError naming `name` and the problem.
#pragma once

#include "pushpull/assets/model.hpp"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace pushpull::assets::detail {

// base_dir: folder external URIs resolve against; empty refuses every external URI.
// refuse_unsupported_required: LoadOptions::refuse_unsupported_required.
void load_gltf(std::span<const std::uint8_t> bytes, const std::string& name,
               const std::filesystem::path& base_dir, const Limits& limits, bool refuse_unsupported_required,
               Model& model);

}  // namespace pushpull::assets::detail
