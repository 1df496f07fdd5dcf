#include "gltf_json_checks.hpp"

#include "pushpull/assets/error.hpp"
#include "uri_policy.hpp"

#include <cstring>

namespace pushpull::assets::detail {

using nlohmann::json;

json parse_json_limited(std::string_view text, const std::string& name, int max_depth) {
  bool too_deep = false;
  json::parser_callback_t limit = [&](int depth, json::parse_event_t, json&) {
    if (depth > max_depth) too_deep = true;
    return !too_deep;
  };
  json document;
  try {
    document = json::parse(text.begin(), text.end(), limit);
  } catch (const json::exception& e) {
    throw AssetError(name + ": malformed JSON: " + e.what());
  }
  if (too_deep) throw AssetError(name + ": JSON nested deeper than " + std::to_string(max_depth) + " levels");
  if (!document.is_object()) throw AssetError(name + ": malformed glTF: the top level is not a JSON object");
  return document;
}

void check_uris(const json& document, const std::string& name) {
  for (const char* kind : {"buffers", "images"}) {
    const auto it = document.find(kind);
    if (it == document.end() || !it->is_array()) continue;
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& entry = (*it)[i];
      if (!entry.is_object() || !entry.contains("uri")) continue;
      if (!entry["uri"].is_string())
        throw AssetError(name + ": " + kind + "[" + std::to_string(i) + "].uri is not a string");
      const std::string uri = entry["uri"].get<std::string>();
      const std::string problem = uri_problem(uri);
      if (!problem.empty())
        throw AssetError(name + ": " + std::string(kind, std::strlen(kind) - 1) + " " + std::to_string(i) +
                         ": uri '" + uri.substr(0, 200) + "' refused: " + problem);
    }
  }
}

std::vector<std::string> string_list(const json& document, const char* key) {
  std::vector<std::string> out;
  const auto it = document.find(key);
  if (it != document.end() && it->is_array())
    for (const json& v : *it)
      if (v.is_string()) out.push_back(v.get<std::string>());
  return out;
}

bool strip_draco_indices(const json& document, std::string& out) {
  json copy;
  bool changed = false;
  const auto meshes = document.find("meshes");
  if (meshes == document.end() || !meshes->is_array()) return false;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& primitive = mesh["primitives"][p];
      if (!primitive.is_object() || !primitive.contains("indices") || !primitive.contains("extensions") ||
          !primitive["extensions"].is_object() ||
          !primitive["extensions"].contains("KHR_draco_mesh_compression"))
        continue;
      if (!changed) copy = document;
      changed = true;
      copy["meshes"][m]["primitives"][p].erase("indices");
    }
  }
  if (changed) out = copy.dump();
  return changed;
}

}  // namespace pushpull::assets::detail
