// write_glb / encode_glb: rebuilds buffers, accessors and meshes from the render side (moved vertices
// through the weld map with rotated normals and tangents; unmoved vertices copied bit for bit),
// carries everything else of the source document through (images: image_carry.hpp).
#include "pushpull/assets/write.hpp"

#include "atomic_file.hpp"
#include "draco_encode.hpp"
#include "glb_container.hpp"
#include "image_carry.hpp"
#include "source_document.hpp"
#include "surface_normals.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace pushpull::assets {

using nlohmann::json;

namespace {

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;

class GlbBuilder {
 public:
  int add_view(const void* data, std::size_t size, int target) {
    bin_.resize((bin_.size() + 3) & ~std::size_t{3}, 0);
    json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    bin_.insert(bin_.end(), bytes, bytes + size);
    views_.push_back(std::move(view));
    return static_cast<int>(views_.size() - 1);
  }

  template <int Cols>
  int add_floats(const RowMatrixXf<Cols>& values, bool with_bounds) {
    static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    json accessor = {{"componentType", kFloat}, {"count", values.rows()}, {"type", kTypes[Cols]}};
    accessor["bufferView"] =
        add_view(values.data(), static_cast<std::size_t>(values.size()) * sizeof(float), kArrayBuffer);
    if (with_bounds && values.rows() > 0) {
      json min = json::array(), max = json::array();
      for (int c = 0; c < Cols; ++c) {
        min.push_back(static_cast<double>(values.col(c).minCoeff()));
        max.push_back(static_cast<double>(values.col(c).maxCoeff()));
      }
      accessor["min"] = min;
      accessor["max"] = max;
    }
    return add_accessor(std::move(accessor));
  }

  int add_indices(const std::vector<std::uint32_t>& indices, Eigen::Index vertex_count) {
    json accessor = {{"count", indices.size()}, {"type", "SCALAR"}};
    if (vertex_count <= 65535) {
      std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
      accessor["componentType"] = kUnsignedShort;
      accessor["bufferView"] = add_view(narrow.data(), narrow.size() * 2, kElementArrayBuffer);
    } else {
      accessor["componentType"] = kUnsignedInt;
      accessor["bufferView"] = add_view(indices.data(), indices.size() * 4, kElementArrayBuffer);
    }
    return add_accessor(std::move(accessor));
  }

  int add_accessor(json accessor) {
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size() - 1);
  }

  json views_ = json::array();
  json accessors_ = json::array();
  std::vector<std::uint8_t> bin_;
};

void erase_from_list(json& document, const char* key, const std::string& value) {
  auto it = document.find(key);
  if (it == document.end() || !it->is_array()) return;
  json kept = json::array();
  for (const json& v : *it)
    if (!(v.is_string() && v.get<std::string>() == value)) kept.push_back(v);
  if (kept.empty())
    document.erase(key);
  else
    *it = kept;
}

void add_to_list(json& document, const char* key, const std::string& value) {
  json& list = document[key];
  if (!list.is_array()) list = json::array();
  for (const json& v : list)
    if (v.is_string() && v.get<std::string>() == value) return;
  list.push_back(value);
}

// One primitive instance rendered back to its node frame after the deformation.
struct Rebuilt {
  RowMatrixXf<3> positions, normals;
  RowMatrixXf<4> tangents;
};

// Render vertices whose deform vertex did not move (deformed position exactly equal to the rest
// position) keep the values read from the file, bit for bit; only moved vertices are rebuilt.
Rebuilt rebuild(const Primitive& primitive, const Eigen::MatrixXd& rest_V, const Eigen::MatrixXd& deformed_V,
                const Eigen::MatrixXd& normals_before, const Eigen::MatrixXd& normals_after,
                std::vector<std::string>& warnings) {
  if (primitive.deform_vertex.size() != static_cast<std::size_t>(primitive.positions.rows()))
    throw AssetError(primitive.name + ": deform_vertex map has " +
                     std::to_string(primitive.deform_vertex.size()) + " entries for " +
                     std::to_string(primitive.positions.rows()) + " vertices");
  for (int d : primitive.deform_vertex)
    if (d >= deformed_V.rows())
      throw AssetError(primitive.name + ": deform_vertex map points past the deformed positions");
  Rebuilt out{primitive.positions, primitive.normals, primitive.tangents};
  const Eigen::Matrix3d L = primitive.T_model_node.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = primitive.T_model_node.topRightCorner<3, 1>();
  const double det = L.determinant();
  const double scale = std::cbrt(std::abs(det));
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det) || L.norm() / scale > 1e9) {
    warnings.push_back(primitive.name + ": singular node transform, written undeformed");
    return out;
  }
  const Eigen::Matrix3d L_inverse = L.inverse();
  const Eigen::Matrix3d normal_matrix = L_inverse.transpose();
  std::vector<bool> moved(static_cast<std::size_t>(out.positions.rows()), false);
  for (Eigen::Index v = 0; v < out.positions.rows(); ++v) {
    const int d = primitive.deform_vertex[static_cast<std::size_t>(v)];
    if (d < 0 || deformed_V.row(d) == rest_V.row(d)) continue;
    moved[static_cast<std::size_t>(v)] = true;
    const Eigen::Vector3d world = deformed_V.row(d).transpose();
    out.positions.row(v) = (L_inverse * (world - t)).transpose().cast<float>();
    const Eigen::Matrix3d R =
        Eigen::Vector3d(normals_before.row(d)).isZero()
            ? Eigen::Matrix3d::Identity()
            : detail::rotation_between(normals_before.row(d).transpose(), normals_after.row(d).transpose());
    if (out.normals.rows() > 0) {
      const Eigen::Vector3d n_world =
          (normal_matrix * primitive.normals.row(v).transpose().cast<double>()).normalized();
      Eigen::Vector3d n_local = (L.transpose() * (R * n_world)).normalized();
      if (!n_local.allFinite() || n_local.isZero())
        n_local = primitive.normals.row(v).transpose().cast<double>();
      out.normals.row(v) = n_local.transpose().cast<float>();
    }
    if (out.tangents.rows() > 0) {
      const Eigen::Vector3d t_local = primitive.tangents.row(v).head<3>().transpose().cast<double>();
      Eigen::Vector3d rotated = (L_inverse * (R * (L * t_local).normalized())).normalized();
      if (!rotated.allFinite() || rotated.isZero()) rotated = Eigen::Vector3d::UnitX();
      out.tangents.row(v).head<3>() = rotated.transpose().cast<float>();
    }
  }
  for (Eigen::Index v = 0; v < out.normals.rows(); ++v) {
    if (!moved[static_cast<std::size_t>(v)]) continue;
    const float n = out.normals.row(v).norm();
    if (std::isfinite(n) && n > 1e-6f)
      out.normals.row(v) /= n;
    else
      out.normals.row(v) << 0.0f, 0.0f, 1.0f;
  }
  for (Eigen::Index v = 0; v < out.tangents.rows(); ++v) {
    if (!moved[static_cast<std::size_t>(v)]) continue;
    const float n = out.tangents.row(v).head<3>().norm();
    if (std::isfinite(n) && n > 1e-6f)
      out.tangents.row(v).head<3>() /= n;
    else
      out.tangents.row(v).head<3>() << 1.0f, 0.0f, 0.0f;
    out.tangents(v, 3) = out.tangents(v, 3) < 0.0f ? -1.0f : 1.0f;
  }
  return out;
}

json write_primitive(GlbBuilder& glb, const Primitive& primitive, const Rebuilt& rebuilt,
                     const WriteOptions& options) {
  json out = json::object();
  json attributes = json::object();
  if (options.draco) {
    detail::DracoEncoded encoded =
        detail::encode_draco(primitive, rebuilt.positions, rebuilt.normals, rebuilt.tangents, options);
    json draco_attributes = json::object();
    for (const auto& [semantic, id] : encoded.attribute_ids) draco_attributes[semantic] = id;
    out["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", glb.add_view(encoded.bytes.data(), encoded.bytes.size(), 0)},
        {"attributes", draco_attributes}};
    for (const auto& [semantic, accessor] : encoded.accessors)
      attributes[semantic] = glb.add_accessor(accessor);
    out["indices"] = glb.add_accessor(encoded.indices_accessor);
  } else {
    attributes["POSITION"] = glb.add_floats(rebuilt.positions, true);
    if (rebuilt.normals.rows() > 0) attributes["NORMAL"] = glb.add_floats(rebuilt.normals, false);
    if (rebuilt.tangents.rows() > 0) attributes["TANGENT"] = glb.add_floats(rebuilt.tangents, false);
    for (std::size_t set = 0; set < primitive.texcoords.size(); ++set)
      if (primitive.texcoords[set].rows() > 0)
        attributes["TEXCOORD_" + std::to_string(set)] = glb.add_floats(primitive.texcoords[set], false);
    if (primitive.colors.rows() > 0) attributes["COLOR_0"] = glb.add_floats(primitive.colors, false);
    out["indices"] = glb.add_indices(primitive.indices, primitive.positions.rows());
  }
  out["attributes"] = attributes;
  out["mode"] = 4;
  if (primitive.material >= 0) out["material"] = primitive.material;
  return out;
}

}  // namespace

namespace {

// What the written file leaves out of the source's meshes, said rather than dropped silently: the writer
// writes the triangles it loaded (the shown scene's), so meshes only on nodes outside that scene, line and
// point primitives, and morph targets with their weights do not reach it.
void dropped_content_warnings(const Model& model, std::vector<std::string>& warnings) {
  const json& source = model.source->json;
  std::set<int> written_nodes;
  for (const Primitive& primitive : model.primitives) written_nodes.insert(primitive.node);
  std::size_t outside = 0;
  if (source.contains("nodes") && source["nodes"].is_array())
    for (std::size_t n = 0; n < source["nodes"].size(); ++n)
      if (source["nodes"][n].is_object() && source["nodes"][n].contains("mesh") &&
          !written_nodes.count(static_cast<int>(n)))
        ++outside;
  if (outside > 0)
    warnings.push_back(
        std::to_string(outside) +
        " node(s) outside the scene shown carry meshes that are not written (their nodes stay, "
        "without the mesh)");
  std::size_t lines_or_points = 0, morphed = 0;
  if (source.contains("meshes") && source["meshes"].is_array())
    for (const json& mesh : source["meshes"]) {
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
      bool targets = mesh.contains("weights");
      for (const json& primitive : mesh["primitives"]) {
        if (!primitive.is_object()) continue;
        const int mode = primitive.contains("mode") && primitive["mode"].is_number_integer()
                             ? primitive["mode"].get<int>()
                             : 4;
        if (mode < 4) ++lines_or_points;
        targets = targets || primitive.contains("targets");
      }
      morphed += targets ? 1 : 0;
    }
  if (lines_or_points > 0)
    warnings.push_back(std::to_string(lines_or_points) + " line or point primitive(s) are not written");
  if (morphed > 0)
    warnings.push_back(
        std::to_string(morphed) +
        " mesh(es) with morph targets are written without them (the deformed base shape only)");
}

}  // namespace

std::vector<std::uint8_t> encode_glb(const Model& model, const Eigen::MatrixXd& deformed_V,
                                     const WriteOptions& options, std::vector<std::string>* warnings_out) {
  std::vector<std::string> warnings;
  if (deformed_V.rows() != model.deform_mesh.V.rows() || deformed_V.cols() != 3)
    throw AssetError("deformed positions are " + std::to_string(deformed_V.rows()) + " by " +
                     std::to_string(deformed_V.cols()) + ", the model has " +
                     std::to_string(model.deform_mesh.V.rows()) + " deform vertices by 3");
  if (!deformed_V.allFinite()) throw AssetError("deformed positions contain non-finite values");
  const Eigen::MatrixXd normals_before = detail::vertex_normals(model.deform_mesh.V, model.deform_mesh.F);
  const Eigen::MatrixXd normals_after = detail::vertex_normals(deformed_V, model.deform_mesh.F);

  json document = model.source ? model.source->json : json::object();
  for (const char* key : {"buffers", "bufferViews", "accessors", "meshes", "skins", "animations"})
    document.erase(key);
  if (model.source && (model.source->json.contains("skins") || model.source->json.contains("animations")))
    warnings.push_back("skins and animations are not written");
  if (model.source) dropped_content_warnings(model, warnings);
  document["asset"]["version"] = "2.0";
  document["asset"]["generator"] = "pushpull";
  document["asset"].erase("minVersion");
  erase_from_list(document, "extensionsUsed", "KHR_draco_mesh_compression");
  erase_from_list(document, "extensionsRequired", "KHR_draco_mesh_compression");
  erase_from_list(document, "extensionsUsed", "KHR_mesh_quantization");
  erase_from_list(document, "extensionsRequired", "KHR_mesh_quantization");
  if (options.draco) {
    add_to_list(document, "extensionsUsed", "KHR_draco_mesh_compression");
    add_to_list(document, "extensionsRequired", "KHR_draco_mesh_compression");
  }
  if (!document["nodes"].is_array()) document["nodes"] = json::array();
  json& nodes = document["nodes"];
  for (json& node : nodes)
    for (const char* key : {"mesh", "skin", "weights"}) node.erase(key);
  if (!document["scenes"].is_array() || document["scenes"].empty()) {
    document["scenes"] = json::array({json{{"nodes", json::array()}}});
    document["scene"] = 0;
  }
  if (!document.contains("scene")) document["scene"] = 0;

  GlbBuilder glb;
  // Images first, in their original order so texture indices stay valid.
  json images = detail::carry_images(
      model, options.output_dir,
      [&glb](const std::vector<std::uint8_t>& bytes) { return glb.add_view(bytes.data(), bytes.size(), 0); },
      warnings);
  if (images.empty())
    document.erase("images");
  else
    document["images"] = std::move(images);

  // One mesh per node (instances deform independently); primitives without a node get a new node.
  json meshes = json::array();
  std::map<std::pair<int, int>, std::vector<std::size_t>> groups;  // (node, mesh if node < 0) -> primitives
  for (std::size_t p = 0; p < model.primitives.size(); ++p) {
    const Primitive& primitive = model.primitives[p];
    groups[{primitive.node, primitive.node >= 0 ? 0 : primitive.mesh}].push_back(p);
  }
  for (const auto& [key, members] : groups) {
    json mesh = {{"primitives", json::array()}};
    const Primitive& first = model.primitives[members.front()];
    if (model.source && first.mesh >= 0) {
      const json& source_meshes = model.source->json["meshes"];
      if (source_meshes.is_array() && first.mesh < static_cast<int>(source_meshes.size()) &&
          source_meshes[static_cast<std::size_t>(first.mesh)].is_object())
        for (const char* key : {"name", "extras"})
          if (source_meshes[static_cast<std::size_t>(first.mesh)].contains(key))
            mesh[key] = source_meshes[static_cast<std::size_t>(first.mesh)][key];
    }
    for (std::size_t p : members) {
      const Primitive& primitive = model.primitives[p];
      const Rebuilt rebuilt =
          rebuild(primitive, model.deform_mesh.V, deformed_V, normals_before, normals_after, warnings);
      mesh["primitives"].push_back(write_primitive(glb, primitive, rebuilt, options));
    }
    meshes.push_back(std::move(mesh));
    const int mesh_index = static_cast<int>(meshes.size() - 1);
    if (key.first >= 0 && key.first < static_cast<int>(nodes.size())) {
      nodes[static_cast<std::size_t>(key.first)]["mesh"] = mesh_index;
    } else {
      json node = {{"name", first.name}, {"mesh", mesh_index}};
      // A plain mesh's primitive keeps its positions relative to its centre (load_model.cpp): the node
      // carries the rest of its transform.
      if (!first.T_model_node.isIdentity(0.0)) {
        json matrix = json::array();
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) matrix.push_back(first.T_model_node(r, c));  // column-major
        node["matrix"] = std::move(matrix);
      }
      nodes.push_back(std::move(node));
      const int scene = document["scene"].is_number_integer() ? document["scene"].get<int>() : 0;
      document["scenes"][static_cast<std::size_t>(
          std::clamp(scene, 0, static_cast<int>(document["scenes"].size()) - 1))]["nodes"]
          .push_back(nodes.size() - 1);
    }
  }
  if (nodes.empty()) document.erase("nodes");
  if (!meshes.empty()) document["meshes"] = std::move(meshes);
  if (!glb.accessors_.empty()) document["accessors"] = std::move(glb.accessors_);
  if (!glb.views_.empty()) {
    document["bufferViews"] = std::move(glb.views_);
    glb.bin_.resize((glb.bin_.size() + 3) & ~std::size_t{3}, 0);
    document["buffers"] = json::array({json{{"byteLength", glb.bin_.size()}}});
  }
  if (warnings_out) *warnings_out = warnings;
  // (replace: a name from a file name that is not UTF-8 is written with U+FFFD; glTF JSON is UTF-8)
  return detail::write_glb_container(document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                                     glb.bin_);
}

std::vector<std::string> write_glb(const Model& model, const Eigen::MatrixXd& deformed_V,
                                   const std::filesystem::path& path, const WriteOptions& options) {
  std::vector<std::string> warnings;
  WriteOptions with_folder = options;
  if (with_folder.output_dir.empty())
    with_folder.output_dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::vector<std::uint8_t> bytes = encode_glb(model, deformed_V, with_folder, &warnings);
  detail::write_file_atomically(path, bytes);
  return warnings;
}

}  // namespace pushpull::assets
