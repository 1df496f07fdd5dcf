#include "image_carry.hpp"

#include "source_document.hpp"

#include <system_error>

namespace pushpull::assets::detail {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

bool is_data_uri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

// Whether a relative URI resolved against `source_dir` names the same file when resolved against
// `output_dir`, i.e. both are the same folder.
bool same_folder(const fs::path& source_dir, const fs::path& output_dir) {
  if (source_dir.empty() || output_dir.empty()) return false;
  std::error_code ec;
  const bool same = fs::equivalent(source_dir, output_dir, ec);
  return !ec && same;
}

std::string label(std::size_t index, const json& entry, const Image& image) {
  std::string what = image.name;
  if (entry.contains("uri") && entry["uri"].is_string() && !is_data_uri(entry["uri"].get<std::string>()))
    what = entry["uri"].get<std::string>().substr(0, 200);
  return "image " + std::to_string(index) + " '" + what + "'";
}

}  // namespace

json carry_images(const Model& model, const fs::path& output_dir, const AddView& add_view,
                  std::vector<std::string>& warnings) {
  if (model.images.empty()) return json::array();
  const json* source_images = nullptr;
  if (model.source && model.source->json.contains("images") && model.source->json["images"].is_array())
    source_images = &model.source->json["images"];
  const fs::path source_dir = model.source ? model.source->base_dir : fs::path();
  const bool beside_source = same_folder(source_dir, output_dir);

  json images = json::array();
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    const Image& image = model.images[i];
    json entry = source_images && i < source_images->size() && (*source_images)[i].is_object()
                     ? (*source_images)[i]
                     : json::object();
    const bool has_uri = entry.contains("uri") && entry["uri"].is_string();
    const std::string uri = has_uri ? entry["uri"].get<std::string>() : std::string();
    if (image.missing || image.encoded.empty()) {
      if (has_uri) {
        warnings.push_back(
            label(i, entry, image) +
            " is missing or unreadable: written referenced by its URI as it was, not embedded");
      } else {
        entry.erase("bufferView");
        warnings.push_back(label(i, entry, image) + " could not be read: written without data");
      }
      images.push_back(std::move(entry));
      continue;
    }
    if (has_uri && (is_data_uri(uri) || beside_source)) {
      images.push_back(std::move(entry));  // the same URI names the same bytes
      continue;
    }
    const std::string mime = entry.contains("mimeType") && entry["mimeType"].is_string()
                                 ? entry["mimeType"].get<std::string>()
                                 : image.mime_type;
    if (mime.empty()) {
      // glTF needs a mimeType for an embedded image: keep the reference rather than guess one.
      warnings.push_back(label(i, entry, image) +
                         " has an unknown format: written referenced by its URI as it was, relative to " +
                         source_dir.string());
      images.push_back(std::move(entry));
      continue;
    }
    entry.erase("uri");
    entry["bufferView"] = add_view(image.encoded);
    entry["mimeType"] = mime;
    images.push_back(std::move(entry));
  }
  return images;
}

}  // namespace pushpull::assets::detail
