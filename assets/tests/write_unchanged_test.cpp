// A written model changes only what moved: the bytes of unmoved vertices (POSITION, NORMAL, TANGENT
// accessors, parsed back with tinygltf) and every image and URI of the input come back as they were.
#include "test_support.hpp"

#include <pushpull/assets/model.hpp>
#include <pushpull/assets/write.hpp>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <map>

namespace pushpull::assets {
namespace {

using nlohmann::json;
using testing::append;
using testing::base64;
using testing::gltf_data;
using testing::ScratchDir;

bool keep_image_bytes(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
                      int, void*) {
  return true;  // images are compared elsewhere, as JSON and bytes
}

tinygltf::Model parse_gltf_file(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  tinygltf::Model gltf;
  std::string err, warn;
  const bool ok = path.extension() == ".glb" ? loader.LoadBinaryFromFile(&gltf, &err, &warn, path.string())
                                             : loader.LoadASCIIFromFile(&gltf, &err, &warn, path.string());
  EXPECT_TRUE(ok) << path << ": " << err;
  return gltf;
}

tinygltf::Model parse_glb(const std::vector<std::uint8_t>& bytes) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  tinygltf::Model gltf;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&gltf, &err, &warn, bytes.data(),
                                          static_cast<unsigned int>(bytes.size()), ""))
      << err;
  return gltf;
}

// The bytes of element `i` of a float accessor (no sparse substitution: the writer writes none and
// the inputs used here have none).
const unsigned char* element(const tinygltf::Model& gltf, int accessor_index, std::size_t i) {
  const tinygltf::Accessor& accessor = gltf.accessors.at(static_cast<std::size_t>(accessor_index));
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_FALSE(accessor.sparse.isSparse);
  const tinygltf::BufferView& view = gltf.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  const std::size_t size =
      static_cast<std::size_t>(
          tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType))) *
      static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
  const std::size_t stride = view.byteStride != 0 ? view.byteStride : size;
  const std::vector<unsigned char>& data = gltf.buffers.at(static_cast<std::size_t>(view.buffer)).data;
  const std::size_t offset = view.byteOffset + accessor.byteOffset + i * stride;
  EXPECT_LE(offset + size, data.size());
  return data.data() + offset;
}

struct Comparison {
  std::size_t unmoved_vertices = 0;
  std::size_t moved_vertices = 0;
  std::size_t bytes_compared = 0;
  std::size_t differing_values = 0;      // unmoved vertices whose attribute bytes differ
  double max_position_difference = 0.0;  // node-local units
};

// Compares POSITION, NORMAL and TANGENT of every unmoved render vertex of `model` between the source
// document and the written one. Written meshes are one per node, primitives in the model's order.
Comparison compare_unmoved(const Model& model, const Eigen::MatrixXd& deformed_V,
                           const tinygltf::Model& source, const tinygltf::Model& written) {
  Comparison result;
  std::map<int, int> next_primitive_of_node;
  for (const Primitive& primitive : model.primitives) {
    const int k = next_primitive_of_node[primitive.node]++;
    const tinygltf::Primitive& in = source.meshes.at(static_cast<std::size_t>(primitive.mesh))
                                        .primitives.at(static_cast<std::size_t>(primitive.primitive));
    const int written_mesh = written.nodes.at(static_cast<std::size_t>(primitive.node)).mesh;
    const tinygltf::Primitive& out =
        written.meshes.at(static_cast<std::size_t>(written_mesh)).primitives.at(static_cast<std::size_t>(k));
    for (std::size_t v = 0; v < primitive.deform_vertex.size(); ++v) {
      const int d = primitive.deform_vertex[v];
      if (d >= 0 && deformed_V.row(d) != model.deform_mesh.V.row(d)) {
        ++result.moved_vertices;
        continue;
      }
      ++result.unmoved_vertices;
      for (const char* semantic : {"POSITION", "NORMAL", "TANGENT"}) {
        if (!in.attributes.count(semantic)) continue;
        EXPECT_TRUE(out.attributes.count(semantic)) << primitive.name << " lost " << semantic;
        if (!out.attributes.count(semantic)) continue;
        const int width = std::string(semantic) == "TANGENT" ? 4 : 3;
        const unsigned char* a = element(source, in.attributes.at(semantic), v);
        const unsigned char* b = element(written, out.attributes.at(semantic), v);
        result.bytes_compared += 4 * static_cast<std::size_t>(width);
        if (std::memcmp(a, b, 4 * static_cast<std::size_t>(width)) != 0) ++result.differing_values;
        if (std::string(semantic) == "POSITION") {
          float pa[3], pb[3];
          std::memcpy(pa, a, sizeof pa);
          std::memcpy(pb, b, sizeof pb);
          for (int c = 0; c < 3; ++c)
            result.max_position_difference =
                std::max(result.max_position_difference, std::abs(double{pa[c]} - double{pb[c]}));
        }
      }
    }
  }
  return result;
}

TEST(AssetsWriteUnchanged, AsamVehicleNosePullLeavesEveryOtherVertexBitIdentical) {
  const auto path = gltf_data() / "AsamVehicle/vehicle_example.gltf";
  const Model model = load_model(path);
  // Move the deform vertices within 30 cm of the front-most one (+X is forward) by 5 cm forward.
  Eigen::Index front = 0;
  model.deform_mesh.V.col(0).maxCoeff(&front);
  const Eigen::RowVector3d nose = model.deform_mesh.V.row(front);
  Eigen::MatrixXd V = model.deform_mesh.V;
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if ((V.row(v) - nose).norm() < 0.3) V(v, 0) += 0.05;
  std::vector<std::string> warnings;
  const std::vector<std::uint8_t> bytes = encode_glb(model, V, {}, &warnings);
  const Comparison c = compare_unmoved(model, V, parse_gltf_file(path), parse_glb(bytes));
  std::printf(
      "AsamVehicle: %zu unmoved / %zu moved render vertices, %zu bytes compared, %zu differing values, "
      "max |position difference| %.3g m\n",
      c.unmoved_vertices, c.moved_vertices, c.bytes_compared, c.differing_values, c.max_position_difference);
  EXPECT_GT(c.moved_vertices, 0u);
  EXPECT_GT(c.unmoved_vertices, 30'000u);
  EXPECT_EQ(c.differing_values, 0u);
  EXPECT_EQ(c.max_position_difference, 0.0);
}

// A GLB with one node (rotated, scaled by 1/100, far from the origin, as a model in centimetres
// placed in a scene), a 3 by 2 grid of vertices with NORMAL and TANGENT values that are not exactly
// unit length (within glTF's tolerance), so any renormalization or round trip through the node
// transform changes their bits.
std::vector<std::uint8_t> grid_glb() {
  std::vector<std::uint8_t> bin;
  append<float>(bin, {0, 0, 0, 10, 0, 0, 20, 0, 0, 0, 10, 1, 10, 10, 2, 20, 10, 3});        // [0, 72)
  for (int v = 0; v < 6; ++v) append<float>(bin, {0.0999f, 0.0002f * float(v), 0.99501f});  // [72, 144)
  for (int v = 0; v < 6; ++v)
    append<float>(bin, {0.99501f, 0.0001f * float(v), -0.0999f, -1.0f});  // [144, 240)
  append<std::uint16_t>(bin, {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4});       // [240, 264)
  json document = json::parse(R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "grid", "mesh": 0, "rotation": [0.2, 0.3, 0.1, 0.9273618495495704],
               "scale": [0.01, 0.01, 0.01], "translation": [3.7, -1.2, 8.1]}],
    "meshes": [{"name": "grid", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2},
                                               "indices": 3}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0,0,0], "max": [20,10,3]},
      {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC4"},
      {"bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    "bufferViews": [
      {"buffer": 0, "byteOffset": 0, "byteLength": 72},
      {"buffer": 0, "byteOffset": 72, "byteLength": 72},
      {"buffer": 0, "byteOffset": 144, "byteLength": 96},
      {"buffer": 0, "byteOffset": 240, "byteLength": 24}],
    "buffers": [{"byteLength": 264}]
  })");
  std::string text = document.dump();
  while (text.size() % 4 != 0) text += ' ';
  std::vector<std::uint8_t> glb;
  const auto total = static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size());
  append<std::uint32_t>(glb, {0x46546C67u, 2u, total, static_cast<std::uint32_t>(text.size()), 0x4E4F534Au});
  glb.insert(glb.end(), text.begin(), text.end());
  append<std::uint32_t>(glb, {static_cast<std::uint32_t>(bin.size()), 0x004E4942u});
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

TEST(AssetsWriteUnchanged, UnmovedNormalsAndTangentsUnderANodeTransformKeepTheirBytes) {
  const std::vector<std::uint8_t> input = grid_glb();
  const Model model = load_model_from_memory(input, "grid.glb", {});
  ASSERT_EQ(model.deform_mesh.V.rows(), 6);
  Eigen::MatrixXd V = model.deform_mesh.V;
  V(5, 2) += 0.01;  // one corner moves 1 cm
  const std::vector<std::uint8_t> bytes = encode_glb(model, V, {}, nullptr);
  const Comparison c = compare_unmoved(model, V, parse_glb(input), parse_glb(bytes));
  EXPECT_EQ(c.moved_vertices, 1u);
  EXPECT_EQ(c.unmoved_vertices, 5u);
  EXPECT_EQ(c.bytes_compared, 5u * (12 + 12 + 16));
  EXPECT_EQ(c.differing_values, 0u);
  // The moved vertex did move, to where it was asked, in the node's frame.
  const Model again = load_model_from_memory(bytes, "again.glb", {});
  ASSERT_EQ(again.deform_mesh.V.rows(), 6);
  double moved_error = 1.0;
  for (Eigen::Index v = 0; v < 6; ++v)
    moved_error = std::min(moved_error, (again.deform_mesh.V.row(v) - V.row(5)).norm());
  EXPECT_LT(moved_error, 1e-6);
}

// The JSON chunk of a GLB.
json glb_json(const std::vector<std::uint8_t>& glb) {
  std::uint32_t length = 0;
  EXPECT_GE(glb.size(), 20u);
  std::memcpy(&length, glb.data() + 12, 4);
  return json::parse(glb.begin() + 20, glb.begin() + 20 + length);
}

// The bytes of buffer view `index` of a GLB's binary chunk.
std::vector<std::uint8_t> glb_view(const std::vector<std::uint8_t>& glb, const json& document, int index) {
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const std::size_t bin_start = 20 + json_length + 8;
  const json& view = document["bufferViews"][static_cast<std::size_t>(index)];
  const std::size_t offset = bin_start + view.value("byteOffset", std::size_t{0});
  return {glb.begin() + static_cast<std::ptrdiff_t>(offset),
          glb.begin() + static_cast<std::ptrdiff_t>(offset + view["byteLength"].get<std::size_t>())};
}

TEST(AssetsWriteUnchanged, ImagesAndUrisAreWrittenBackAsTheyWere) {
  ScratchDir dir;
  const std::vector<std::uint8_t> png = testing::read_bytes(gltf_data() / "AsamVehicle/License_Plate.png");
  ASSERT_GT(png.size(), 100u);
  testing::write_bytes(dir / "plate.png", png);
  // A triangle, then the PNG again in the buffer (an image stored in a buffer view).
  std::vector<std::uint8_t> bin;
  append<float>(bin, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  bin.insert(bin.end(), png.begin(), png.end());
  const std::string data_uri = "data:image/png;base64," + base64(png);
  json document = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"meshes", json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", 0}}}}})}}})},
      {"accessors", json::array({{{"bufferView", 0},
                                  {"componentType", 5126},
                                  {"count", 3},
                                  {"type", "VEC3"},
                                  {"min", {0, 0, 0}},
                                  {"max", {1, 1, 0}}}})},
      {"bufferViews", json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                                   {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", png.size()}}})},
      {"buffers", json::array({{{"byteLength", bin.size()},
                                {"uri", "data:application/octet-stream;base64," + base64(bin)}}})},
      {"images", json::array({{{"uri", "plate.png"}, {"name", "external"}},
                              {{"uri", "textures/gone.png"}, {"name", "missing"}},
                              {{"bufferView", 1}, {"mimeType", "image/png"}, {"name", "in a buffer view"}},
                              {{"uri", data_uri}, {"name", "data uri"}}})}};
  testing::write_text(dir / "scene.gltf", document.dump());
  const Model model = load_model(dir / "scene.gltf");
  ASSERT_EQ(model.images.size(), 4u);
  Eigen::MatrixXd V = model.deform_mesh.V;
  V(1, 2) = 0.1;

  // Beside the source: every URI stays as it was, the buffer-view image keeps its bytes.
  const auto beside = dir / "deformed.glb";
  const std::vector<std::string> warnings = write_glb(model, V, beside);
  const std::vector<std::uint8_t> glb = testing::read_bytes(beside);
  const json out = glb_json(glb);
  ASSERT_EQ(out["images"].size(), 4u);
  EXPECT_EQ(out["images"][0], document["images"][0]);
  EXPECT_EQ(out["images"][1], document["images"][1]);  // missing: still referenced, no placeholder
  EXPECT_TRUE(out["images"][3] == document["images"][3]) << "the data: URI image changed";
  EXPECT_EQ(out["images"][2]["mimeType"], "image/png");
  EXPECT_EQ(out["images"][2]["name"], "in a buffer view");
  EXPECT_EQ(glb_view(glb, out, out["images"][2]["bufferView"].get<int>()), png);
  bool warned = false;
  for (const std::string& warning : warnings)
    warned = warned || warning.find("textures/gone.png") != std::string::npos;
  EXPECT_TRUE(warned) << "no warning names the missing image";

  // Elsewhere: the external image is embedded with its bytes unchanged (a relative URI would point
  // nowhere); the missing one is still referenced by its URI; the data: URI is unchanged.
  std::filesystem::create_directories(dir / "elsewhere");
  const auto away = dir / "elsewhere" / "deformed.glb";
  write_glb(model, V, away);
  const std::vector<std::uint8_t> glb_away = testing::read_bytes(away);
  const json out_away = glb_json(glb_away);
  ASSERT_EQ(out_away["images"].size(), 4u);
  EXPECT_FALSE(out_away["images"][0].contains("uri"));
  EXPECT_EQ(out_away["images"][0]["name"], "external");
  EXPECT_EQ(out_away["images"][0]["mimeType"], "image/png");
  EXPECT_EQ(glb_view(glb_away, out_away, out_away["images"][0]["bufferView"].get<int>()), png);
  EXPECT_EQ(out_away["images"][1], document["images"][1]);
  EXPECT_TRUE(out_away["images"][3] == document["images"][3]) << "the data: URI image changed";
  EXPECT_EQ(glb_view(glb_away, out_away, out_away["images"][2]["bufferView"].get<int>()), png);
}

}  // namespace
}  // namespace pushpull::assets
