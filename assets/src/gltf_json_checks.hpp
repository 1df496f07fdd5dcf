// Checks on the glTF JSON before tinygltf sees it: well-formed and not nested too deep, buffer and
// image URIs acceptable under the URI policy; and the small rewrites tinygltf 2.7 needs.
// Thread-safety: pure functions. Errors throw AssetError naming `name`.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace pushpull::assets::detail {

// Parses `text`; refuses malformed JSON, nesting deeper than max_depth and a non-object top level.
nlohmann::json parse_json_limited(std::string_view text, const std::string& name, int max_depth);

// Refuses buffers[i].uri / images[i].uri that the URI policy rejects (see uri_policy.hpp).
void check_uris(const nlohmann::json& document, const std::string& name);

// The string entries of the top-level array `key` (e.g. extensionsUsed); empty when absent.
std::vector<std::string> string_list(const nlohmann::json& document, const char* key);

// Writes into `out` the document without "indices" on Draco-compressed primitives (tinygltf 2.7
// built without Draco requires a bufferView on index accessors); false, `out` untouched, when none.
bool strip_draco_indices(const nlohmann::json& document, std::string& out);

}  // namespace pushpull::assets::detail
