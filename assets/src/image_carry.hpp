// Images of a loaded model written back as they were read (used by the GLB writer).
//
// Rules, per image of the source document, in its original order so texture indices stay valid:
//  - a data: URI stays the same data: URI;
//  - an external URI stays the same URI when the written file sits in the folder the URI resolved
//    against (it still names the same file); written anywhere else, the image's bytes are embedded
//    unchanged (a relative URI would point nowhere), with its mimeType;
//  - an image that was missing or unreadable stays referenced by its URI as it was, with a warning;
//    nothing is ever replaced by a placeholder;
//  - an image stored in a buffer view is embedded with the same bytes and mimeType.
// Every other member of an image entry (name, extensions, extras) is carried through unchanged.
// Thread-safety: pure function of its arguments.
#pragma once

#include "pushpull/assets/model.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pushpull::assets::detail {

// Appends bytes to the binary chunk as a new buffer view and returns its index.
using AddView = std::function<int(const std::vector<std::uint8_t>& bytes)>;

// The "images" array to write for `model` (empty when the model has no images). `output_dir`: the
// folder the written file will sit in (empty: unknown, every present image is embedded).
nlohmann::json carry_images(const Model& model, const std::filesystem::path& output_dir,
                            const AddView& add_view, std::vector<std::string>& warnings);

}  // namespace pushpull::assets::detail
