#include "gltf_loader.hpp"

#include "accessor_reader.hpp"
#include "draco_decode.hpp"
#include "glb_container.hpp"
#include "gltf_json_checks.hpp"
#include "image_header.hpp"
#include "primitive_build.hpp"
#include "source_document.hpp"
#include "uri_policy.hpp"

#include <tiny_gltf.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

namespace pushpull::assets::detail {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Extensions the loader interprets; every other used extension is named in a warning.
const std::set<std::string> kInterpretedExtensions = {"KHR_draco_mesh_compression", "KHR_mesh_quantization"};
// Extensions without which the geometry cannot be read: refused when required.
const std::set<std::string> kGeometryExtensions = {"EXT_meshopt_compression", "KHR_meshopt_compression"};

// A required extension pushpull does not interpret is refused (glTF 2.0: a loader must not load an asset
// whose required extension it does not support), except those known to change only how the model looks (its
// materials, textures, lights, metadata): without them the shape under review is the file's, drawn with the
// base material. Any other (EXT_mesh_gpu_instancing places copies of meshes; an unknown one may move
// vertices) could leave the reviewed shape other than the file's. A list, not prefixes: a future material
// extension may displace the surface.
const std::set<std::string> kAppearanceOnlyExtensions = {"KHR_materials_anisotropy",
                                                         "KHR_materials_clearcoat",
                                                         "KHR_materials_diffuse_transmission",
                                                         "KHR_materials_dispersion",
                                                         "KHR_materials_emissive_strength",
                                                         "KHR_materials_ior",
                                                         "KHR_materials_iridescence",
                                                         "KHR_materials_pbrSpecularGlossiness",
                                                         "KHR_materials_sheen",
                                                         "KHR_materials_specular",
                                                         "KHR_materials_transmission",
                                                         "KHR_materials_unlit",
                                                         "KHR_materials_variants",
                                                         "KHR_materials_volume",
                                                         "KHR_texture_basisu",
                                                         "KHR_texture_transform",
                                                         "EXT_texture_webp",
                                                         "EXT_texture_avif",
                                                         "MSFT_texture_dds",
                                                         "MSFT_packing_normalRoughnessMetallic",
                                                         "MSFT_packing_occlusionRoughnessMetallic",
                                                         "KHR_lights_punctual",
                                                         "EXT_lights_image_based",
                                                         "KHR_xmp_json_ld"};

// ---- file access under the URI policy (tinygltf FsCallbacks) ----

struct FsContext {
  fs::path root;  // canonical folder of the model, empty = no external files
  std::uint64_t max_bytes = 0;
  std::string refusal;  // first refusal, for the error message
  std::vector<fs::path> read;  // the external files read
};

bool allowed(FsContext& context, const std::string& path) {
  if (context.root.empty()) {
    if (context.refusal.empty()) context.refusal = "external file '" + path + "' (no base folder)";
    return false;
  }
  if (!path_is_inside(context.root, path)) {
    if (context.refusal.empty()) context.refusal = "'" + path + "' resolves outside the model's folder";
    return false;
  }
  return true;
}

bool fs_file_exists(const std::string& path, void* user) {
  auto& context = *static_cast<FsContext*>(user);
  std::error_code ec;
  // A file that is not there is not refused (tinygltf tries several places and then names the file it did
  // not find); one that is there must be inside the model's folder.
  if (!fs::is_regular_file(path, ec)) return false;
  return allowed(context, path);
}

std::string fs_expand_path(const std::string& path, void*) {
  return path;
}  // no ~ or $VAR expansion

bool fs_read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                        void* user) {
  auto& context = *static_cast<FsContext*>(user);
  if (!allowed(context, path)) {
    if (err) *err += "refused: " + context.refusal + "\n";
    return false;
  }
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec || size > context.max_bytes) {
    if (err) *err += "'" + path + "' is too large or unreadable\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(size);
  if (size > 0 && !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    if (err) *err += "cannot read '" + path + "'\n";
    return false;
  }
  context.read.emplace_back(path);
  return true;
}

bool fs_write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing through the loader is not allowed\n";
  return false;
}

// Keeps images encoded (decoding is the renderer's business); reads only their header.
bool keep_image_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  const ImageHeader header =
      read_image_header(std::span<const std::uint8_t>(bytes, static_cast<std::size_t>(std::max(size, 0))));
  image->width = header.width;
  image->height = header.height;
  image->component = 4;
  return true;
}

// ---- materials, textures, images ----

TextureRef texture_ref(const tinygltf::Model& gltf, int index, int texcoord, double scale,
                       const std::string& where, std::vector<std::string>& warnings) {
  TextureRef ref;
  if (index < 0) return ref;
  if (index >= static_cast<int>(gltf.textures.size())) {
    warnings.push_back(where + ": texture " + std::to_string(index) + " does not exist (ignored)");
    return ref;
  }
  ref.texture = index;
  ref.texcoord = std::clamp(texcoord, 0, 7);
  ref.scale = static_cast<float>(scale);
  return ref;
}

void convert_materials(const tinygltf::Model& gltf, Model& model) {
  auto& warnings = model.report.warnings;
  for (std::size_t i = 0; i < gltf.materials.size(); ++i) {
    const tinygltf::Material& m = gltf.materials[i];
    const std::string where = "material " + std::to_string(i) + " '" + m.name + "'";
    Material out;
    out.name = m.name;
    const auto& pbr = m.pbrMetallicRoughness;
    for (std::size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c)
      out.base_color_factor[static_cast<Eigen::Index>(c)] = static_cast<float>(pbr.baseColorFactor[c]);
    out.base_color_texture =
        texture_ref(gltf, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, 1.0, where, warnings);
    out.metallic_factor = static_cast<float>(pbr.metallicFactor);
    out.roughness_factor = static_cast<float>(pbr.roughnessFactor);
    out.metallic_roughness_texture = texture_ref(gltf, pbr.metallicRoughnessTexture.index,
                                                 pbr.metallicRoughnessTexture.texCoord, 1.0, where, warnings);
    out.normal_texture = texture_ref(gltf, m.normalTexture.index, m.normalTexture.texCoord,
                                     m.normalTexture.scale, where, warnings);
    out.occlusion_texture = texture_ref(gltf, m.occlusionTexture.index, m.occlusionTexture.texCoord,
                                        m.occlusionTexture.strength, where, warnings);
    out.emissive_texture =
        texture_ref(gltf, m.emissiveTexture.index, m.emissiveTexture.texCoord, 1.0, where, warnings);
    for (std::size_t c = 0; c < 3 && c < m.emissiveFactor.size(); ++c)
      out.emissive_factor[static_cast<Eigen::Index>(c)] = static_cast<float>(m.emissiveFactor[c]);
    out.alpha_mode = m.alphaMode == "MASK"    ? AlphaMode::mask
                     : m.alphaMode == "BLEND" ? AlphaMode::blend
                                              : AlphaMode::opaque;
    out.alpha_cutoff = static_cast<float>(m.alphaCutoff);
    out.double_sided = m.doubleSided;
    for (const auto& [extension, value] : m.extensions) out.extensions.push_back(extension);
    model.materials.push_back(std::move(out));
  }
  for (const tinygltf::Sampler& s : gltf.samplers)
    model.samplers.push_back({s.magFilter, s.minFilter, s.wrapS, s.wrapT});
  for (const tinygltf::Texture& t : gltf.textures) {
    Texture out{t.name, t.source, t.sampler};
    if (out.image >= static_cast<int>(gltf.images.size())) out.image = -1;
    if (out.sampler >= static_cast<int>(gltf.samplers.size())) out.sampler = -1;
    model.textures.push_back(out);
  }
  for (std::size_t i = 0; i < gltf.images.size(); ++i) {
    const tinygltf::Image& image = gltf.images[i];
    Image out;
    out.name = image.name;
    out.encoded.assign(image.image.begin(), image.image.end());
    out.mime_type = read_image_header(out.encoded).mime_type;
    if (out.mime_type.empty() && !out.encoded.empty())  // the bytes decide, not the JSON's mimeType
      warnings.push_back("image " + std::to_string(i) + " '" + image.name +
                         "' is not PNG, JPEG, WebP or KTX2 data");
    out.width = std::max(image.width, 0);
    out.height = std::max(image.height, 0);
    out.missing = out.encoded.empty();
    if (out.missing)
      warnings.push_back("image " + std::to_string(i) + " '" +
                         (image.uri.empty() ? image.name : image.uri.substr(0, 200)) +
                         "' is missing or unreadable (textures using it render untextured)");
    model.images.push_back(std::move(out));
  }
}

// ---- meshes and the node hierarchy ----

Eigen::Matrix4d local_transform(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(c * 4 + r)];
    return m;
  }
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3)
    t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4) {
    Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (q.norm() > 1e-12) t.rotate(q.normalized());
  }
  if (node.scale.size() == 3) t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return t.matrix();
}

class Flattener {
 public:
  Flattener(const tinygltf::Model& gltf, const json& document, const std::string& name, const Limits& limits,
            Model& model)
      : gltf_(gltf),
        document_(document),
        name_(name),
        limits_(limits),
        model_(model),
        reader_{gltf, name, limits} {}

  void run() {
    std::vector<int> roots;
    if (!gltf_.scenes.empty()) {
      int scene = gltf_.defaultScene >= 0 && gltf_.defaultScene < static_cast<int>(gltf_.scenes.size())
                      ? gltf_.defaultScene
                      : 0;
      roots = gltf_.scenes[static_cast<std::size_t>(scene)].nodes;
    } else {
      std::vector<bool> is_child(gltf_.nodes.size(), false);
      for (const auto& node : gltf_.nodes)
        for (int c : node.children)
          if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[static_cast<std::size_t>(c)] = true;
      for (std::size_t i = 0; i < gltf_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
      if (gltf_.nodes.empty())
        for (std::size_t m = 0; m < gltf_.meshes.size(); ++m)
          add_mesh(-1, static_cast<int>(m), Eigen::Matrix4d::Identity());
    }
    struct Item {
      int node;
      Eigen::Matrix4d T_model_parent;
      int depth;
    };
    std::vector<Item> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.push_back({*it, Eigen::Matrix4d::Identity(), 0});
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      if (item.node < 0 || item.node >= static_cast<int>(gltf_.nodes.size()))
        throw AssetError(name_ + ": node " + std::to_string(item.node) + " does not exist");
      if (item.depth > limits_.max_node_depth)
        throw AssetError(name_ + ": node hierarchy deeper than " + std::to_string(limits_.max_node_depth) +
                         " (a cycle?)");
      if (++visits_ > limits_.max_instances)
        throw AssetError(name_ + ": more than " + std::to_string(limits_.max_instances) +
                         " node instances (a cycle or shared children?)");
      const tinygltf::Node& node = gltf_.nodes[static_cast<std::size_t>(item.node)];
      const Eigen::Matrix4d T_model_node = item.T_model_parent * local_transform(node);
      if (!T_model_node.allFinite())
        throw AssetError(name_ + ": node " + std::to_string(item.node) + " has a non-finite transform");
      if (node.mesh >= 0) add_mesh(item.node, node.mesh, T_model_node);
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
        stack.push_back({*it, T_model_node, item.depth + 1});
    }
  }

 private:
  void add_mesh(int node, int mesh_index, const Eigen::Matrix4d& T_model_node) {
    if (mesh_index >= static_cast<int>(gltf_.meshes.size()))
      throw AssetError(name_ + ": mesh " + std::to_string(mesh_index) + " does not exist");
    const tinygltf::Mesh& mesh = gltf_.meshes[static_cast<std::size_t>(mesh_index)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = name_ + ": mesh " + std::to_string(mesh_index) + " '" + mesh.name +
                                "' primitive " + std::to_string(p);
      const tinygltf::Primitive& source = mesh.primitives[p];
      if (source.mode != TINYGLTF_MODE_TRIANGLES && source.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          source.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        model_.report.warnings.push_back(where + ": mode " + std::to_string(source.mode) +
                                         " (points/lines) skipped");
        continue;
      }
      if (!source.targets.empty() && !warned_targets_) {
        model_.report.warnings.push_back(where + ": morph targets are ignored (base shape used)");
        warned_targets_ = true;
      }
      Primitive primitive = decode(mesh_index, static_cast<int>(p), source, where);
      primitive.node = node;
      primitive.mesh = mesh_index;
      primitive.primitive = static_cast<int>(p);
      primitive.material = source.material >= 0 && source.material < static_cast<int>(gltf_.materials.size())
                               ? source.material
                               : -1;
      if (source.material >= static_cast<int>(gltf_.materials.size()))
        model_.report.warnings.push_back(where + ": material " + std::to_string(source.material) +
                                         " does not exist (default used)");
      const std::string node_name =
          node >= 0 ? gltf_.nodes[static_cast<std::size_t>(node)].name : std::string();
      primitive.name = node_name + "/" + mesh.name + "#" + std::to_string(p);
      primitive.T_model_node = T_model_node;
      total_vertices_ += static_cast<std::uint64_t>(primitive.positions.rows());
      total_triangles_ += primitive.indices.size() / 3;
      if (total_vertices_ > limits_.max_vertices || total_triangles_ > limits_.max_triangles)
        throw AssetError(name_ + ": more than " + std::to_string(limits_.max_vertices) + " vertices or " +
                         std::to_string(limits_.max_triangles) + " triangles after instancing");
      model_.primitives.push_back(std::move(primitive));
      if (model_.primitives.size() > limits_.max_instances)
        throw AssetError(name_ + ": too many primitive instances");
    }
  }

  // Decoded once per (mesh, primitive), copied for each further instance.
  Primitive decode(int mesh_index, int p, const tinygltf::Primitive& source, const std::string& where) {
    const auto key = std::make_pair(mesh_index, p);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    Primitive out;
    const json* draco = nullptr;
    const json& prim_json = document_.at("meshes")
                                .at(static_cast<std::size_t>(mesh_index))
                                .at("primitives")
                                .at(static_cast<std::size_t>(p));
    if (auto ext = prim_json.find("extensions"); ext != prim_json.end() && ext->is_object())
      if (auto d = ext->find("KHR_draco_mesh_compression"); d != ext->end()) draco = &*d;
    if (draco) {
      if (!draco->is_object() || !draco->contains("bufferView") ||
          !(*draco)["bufferView"].is_number_integer() || !draco->contains("attributes") ||
          !(*draco)["attributes"].is_object())
        throw AssetError(where + ": malformed KHR_draco_mesh_compression extension");
      const int view = (*draco)["bufferView"].get<int>();
      const auto& bv = view >= 0 && view < static_cast<int>(gltf_.bufferViews.size())
                           ? gltf_.bufferViews[static_cast<std::size_t>(view)]
                           : throw AssetError(where + ": Draco bufferView does not exist");
      auto [bytes, stride] = reader_.view_bytes(-1, view, 0, 1, bv.byteLength, false);
      std::vector<std::pair<std::string, int>> ids;
      for (const auto& [semantic, id] : (*draco)["attributes"].items()) {
        if (!id.is_number_integer())
          throw AssetError(where + ": Draco attribute id of " + semantic + " is not an integer");
        ids.emplace_back(semantic, id.get<int>());
      }
      DecodedDraco decoded = decode_draco(std::span(bytes, bv.byteLength), ids, where, limits_.max_vertices,
                                          limits_.max_triangles);
      for (auto& [semantic, values] : decoded.attributes)
        assign_attribute(out, semantic, std::move(values), where);
      // Attributes outside the Draco payload (allowed by the extension) come from accessors.
      for (const auto& attribute : source.attributes) {
        const std::string& semantic = attribute.first;
        if (std::none_of(ids.begin(), ids.end(),
                         [&semantic](const auto& id) { return id.first == semantic; })) {
          FloatRows values = reader_.read_floats(attribute.second);
          if (values.rows() == static_cast<Eigen::Index>(decoded.points))
            assign_attribute(out, semantic, std::move(values), where);
        }
      }
      assign_triangles(out, TINYGLTF_MODE_TRIANGLES, std::move(decoded.indices), true, where);
    } else {
      const auto position = source.attributes.find("POSITION");
      if (position == source.attributes.end()) throw AssetError(where + ": no POSITION attribute");
      // glTF 2.0 positions are floats; integer ones only under KHR_mesh_quantization (read as their values,
      // the file's own scale in the node's matrix), else they were unsigned integers read as metres.
      if (position->second >= 0 && static_cast<std::size_t>(position->second) < gltf_.accessors.size() &&
          gltf_.accessors[static_cast<std::size_t>(position->second)].componentType !=
              TINYGLTF_COMPONENT_TYPE_FLOAT &&
          std::find(gltf_.extensionsUsed.begin(), gltf_.extensionsUsed.end(), "KHR_mesh_quantization") ==
              gltf_.extensionsUsed.end())
        throw AssetError(
            where + ": POSITION accessor " + std::to_string(position->second) +
            " is not of floats (componentType " +
            std::to_string(gltf_.accessors[static_cast<std::size_t>(position->second)].componentType) +
            ", 5126 = FLOAT; integers need KHR_mesh_quantization)");
      for (const auto& [semantic, accessor] : source.attributes) {
        if (semantic != "POSITION" && semantic != "NORMAL" && semantic != "TANGENT" &&
            semantic != "COLOR_0" && semantic.rfind("TEXCOORD_", 0) != 0)
          continue;
        assign_attribute(out, semantic, reader_.read_floats(accessor), where);
      }
      std::vector<std::uint32_t> indices;
      if (source.indices >= 0) indices = reader_.read_indices(source.indices);
      assign_triangles(out, source.mode, std::move(indices), source.indices >= 0, where);
    }
    check_primitive(out, where);
    cache_.emplace(key, out);
    return out;
  }

  const tinygltf::Model& gltf_;
  const json& document_;
  const std::string& name_;
  const Limits& limits_;
  Model& model_;
  AccessorReader reader_;
  std::map<std::pair<int, int>, Primitive> cache_;
  std::uint64_t visits_ = 0;
  std::uint64_t total_vertices_ = 0;
  std::uint64_t total_triangles_ = 0;
  bool warned_targets_ = false;
};

// Writes into `out` the document without "indices" on Draco-compressed primitives; false when
// there are none (then `out` is untouched).
void split_lines(const std::string& text, const std::string& prefix, std::vector<std::string>& out) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) out.push_back(prefix + text.substr(start, std::min<std::size_t>(end - start, 400)));
    start = end + 1;
  }
}

// tinygltf's messages quote a data: URI whole (megabytes of base64): each payload is cut to its first
// characters and its length.
std::string shorten_data_uris(std::string text) {
  constexpr std::size_t kKept = 16;
  for (std::size_t at = text.find("data:"); at != std::string::npos; at = text.find("data:", at + 5)) {
    // The URI ends at white space, a quote, a backslash (an escaped quote) or a closing bracket; its payload
    // follows the first comma within it.
    const std::size_t uri_end = std::min(text.find_first_of(" \t\r\n'\"\\)]", at), text.size());
    const std::size_t comma = text.find(',', at);
    if (comma == std::string::npos || comma >= uri_end) continue;
    const std::size_t payload = uri_end - (comma + 1);
    const std::string cut = "... (" + std::to_string(payload) + " characters)";
    if (payload <= kKept + cut.size()) continue;  // no shorter for it
    text.replace(comma + 1 + kKept, payload - kKept, cut);
  }
  return text;
}

}  // namespace

void load_gltf(std::span<const std::uint8_t> bytes, const std::string& name, const fs::path& base_dir,
               const Limits& limits, bool refuse_unsupported_required, Model& model) {
  const bool binary = looks_like_glb(bytes);
  // A .glb that is not one (empty, cut, another format renamed) is named so, not parsed as glTF's JSON.
  std::string extension = fs::path(name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!binary && extension == ".glb")
    throw AssetError(name + ": not a GLB file (" + std::to_string(bytes.size()) +
                     " bytes; a GLB begins with the 12-byte header 'glTF', version 2, length)");
  std::string_view json_text;
  if (binary) {
    json_text = parse_glb(bytes, name).json;
  } else {
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  model.report.format = binary ? "GLB" : "glTF";
  auto source = std::make_shared<SourceDocument>();
  source->json = parse_json_limited(json_text, name, limits.max_json_depth);
  const json& document = source->json;
  check_uris(document, name);
  // What makes it glTF 2.0 (tinygltf says "JSON string too short." of an object without it).
  if (!document.is_object() || !document.contains("asset") || !document["asset"].is_object() ||
      !document["asset"].contains("version") || !document["asset"]["version"].is_string())
    throw AssetError(name + ": not a glTF 2.0 file: no \"asset\" object with its \"version\"");
  if (const std::string version = document["asset"]["version"].get<std::string>();
      version.rfind("2.", 0) != 0)
    throw AssetError(name + ": glTF version \"" + version +
                     "\": only glTF 2.x is read (glTF 1.0 is another format)");
  // tinygltf indexes these arrays without checking their types: make sure they are arrays.
  for (const char* key : {"meshes", "nodes", "accessors", "bufferViews", "buffers", "materials", "textures",
                          "images", "samplers", "scenes"})
    if (document.contains(key) && !document[key].is_array())
      throw AssetError(name + ": malformed glTF: '" + key + "' is not an array");
  // The scene shown: one that is not there is damage, not a reason to show another one silently.
  if (document.contains("scene")) {
    const json& scene = document["scene"];
    const std::size_t scenes = document.contains("scenes") ? document["scenes"].size() : 0;
    if (!scene.is_number_unsigned() || scene.get<std::uint64_t>() >= scenes)
      throw AssetError(name + ": malformed glTF: \"scene\" " + scene.dump() + " names none of its " +
                       std::to_string(scenes) + " scene(s)");
  }

  model.report.extensions_used = string_list(document, "extensionsUsed");
  model.report.extensions_required = string_list(document, "extensionsRequired");
  std::set<std::string> said;  // required extensions that may change the geometry, said once (info)
  for (const std::string& extension : model.report.extensions_required)
    if (kGeometryExtensions.count(extension)) {
      throw AssetError(name + ": requires extension " + extension + ", which pushpull cannot decode");
    } else if (!kInterpretedExtensions.count(extension) && !kAppearanceOnlyExtensions.count(extension)) {
      if (refuse_unsupported_required)
        throw AssetError(name + ": requires extension " + extension +
                         ", which pushpull does not support (it may change the model's geometry; extensions "
                         "that change only materials, textures or lights are drawn without)");
      model.report.warnings.push_back("extension " + extension +
                                      " (required) may change the geometry and is not supported: deform, "
                                      "render and review refuse this file");
      said.insert(extension);
    }
  for (const std::string& extension : model.report.extensions_used)
    if (!kInterpretedExtensions.count(extension)) {
      model.report.unsupported_extensions.push_back(extension);
      if (said.count(extension)) continue;
      const bool required =
          std::find(model.report.extensions_required.begin(), model.report.extensions_required.end(),
                    extension) != model.report.extensions_required.end();
      model.report.warnings.push_back(
          "extension " + extension + (required ? " (required)" : "") +
          " is not supported: ignored for rendering, carried through to written files");
    }

  FsContext context;
  std::error_code ec;
  if (!base_dir.empty()) context.root = fs::weakly_canonical(fs::absolute(base_dir, ec), ec);
  if (ec) context.root.clear();
  source->base_dir = context.root;
  context.max_bytes = limits.max_file_bytes;

  // tinygltf 2.7 (built without Draco) insists that a primitive's index accessor has a bufferView,
  // which Draco-compressed primitives lack: hand it a copy without those indices (they come from
  // the Draco payload).
  std::string patched_json;
  std::vector<std::uint8_t> patched_glb;
  if (strip_draco_indices(document, patched_json)) {
    if (binary) {
      patched_glb = write_glb_container(patched_json, parse_glb(bytes, name).bin);
      bytes = patched_glb;
    } else {
      json_text = patched_json;
    }
  }

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fs_file_exists, &fs_expand_path, &fs_read_whole_file,
                                              &fs_write_whole_file, &context});
  loader.SetImageLoader(&keep_image_encoded, nullptr);
  tinygltf::Model gltf;
  std::string err, warn;
  const std::string base = context.root.string();
  bool ok = false;
  try {
    if (binary)
      ok = loader.LoadBinaryFromMemory(&gltf, &err, &warn, bytes.data(),
                                       static_cast<unsigned int>(bytes.size()), base);
    else
      ok = loader.LoadASCIIFromString(&gltf, &err, &warn, json_text.data(),
                                      static_cast<unsigned int>(json_text.size()), base);
  } catch (const std::exception& e) {
    throw AssetError(name + ": malformed glTF: " + e.what());
  }
  if (!context.refusal.empty() && !ok) throw AssetError(name + ": refused: " + context.refusal);
  if (!ok) {
    std::string message = err.empty() ? "tinygltf could not parse it" : shorten_data_uris(err);
    while (!message.empty() && message.back() == '\n') message.pop_back();
    if (message.size() > 400) message = message.substr(0, 400) + "...";  // data: URIs can be huge
    throw AssetError(name + ": " + message);
  }
  split_lines(shorten_data_uris(warn), name + ": ", model.report.warnings);
  if (!gltf.skins.empty() || !gltf.animations.empty())
    model.report.warnings.push_back(name + ": skins and animations are ignored (rest pose used)");

  model.source_files.insert(model.source_files.end(), context.read.begin(), context.read.end());
  convert_materials(gltf, model);
  try {
    Flattener(gltf, document, name, limits, model).run();
  } catch (const json::exception& e) {
    throw AssetError(name + ": malformed glTF: " + e.what());
  }
  model.source = std::move(source);
}

}  // namespace pushpull::assets::detail
