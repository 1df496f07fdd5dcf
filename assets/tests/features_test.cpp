// glTF features beyond the sample assets: instancing with a mirroring transform, node matrices,
// triangle strips, non-indexed primitives, normalized integer texcoords, sparse accessors,
// embedded data: URIs; and the GLB written from them validates.
#include "test_support.hpp"

#include <pushpull/assets/model.hpp>
#include <pushpull/assets/write.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cstring>

namespace pushpull::assets {
namespace {

using testing::append;
using testing::base64;

nlohmann::json features_document() {
  std::vector<std::uint8_t> bin;
  append<float>(bin, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});              // [0, 48) quad positions
  append<std::uint8_t>(bin, {0, 1, 3, 2});                               // [48, 52) strip
  append<std::uint16_t>(bin, {0, 0, 65535, 0, 65535, 65535, 0, 65535});  // [52, 68) normalized UVs
  append<std::uint8_t>(bin, {2, 0, 0, 0});                               // [68, 72) sparse index (+pad)
  append<float>(bin, {1, 1, 0.5f});                                      // [72, 84) sparse value
  return nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [3]}],
    "nodes": [
      {"mesh": 0, "translation": [2, 0, 0]},
      {"mesh": 0, "scale": [-1, 1, 1]},
      {"mesh": 1, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]},
      {"name": "root", "children": [0, 1, 2]}],
    "meshes": [
      {"name": "strip", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "mode": 5}]},
      {"name": "sparse", "primitives": [{"attributes": {"POSITION": 3}}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
      {"bufferView": 1, "componentType": 5121, "count": 4, "type": "SCALAR"},
      {"bufferView": 2, "componentType": 5123, "normalized": true, "count": 4, "type": "VEC2"},
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0.5],
       "sparse": {"count": 1, "indices": {"bufferView": 3, "componentType": 5121}, "values": {"bufferView": 4}}}],
    "bufferViews": [
      {"buffer": 0, "byteOffset": 0, "byteLength": 48},
      {"buffer": 0, "byteOffset": 48, "byteLength": 4},
      {"buffer": 0, "byteOffset": 52, "byteLength": 16},
      {"buffer": 0, "byteOffset": 68, "byteLength": 1},
      {"buffer": 0, "byteOffset": 72, "byteLength": 12}],
    "buffers": [{"byteLength": 84, "uri": "data:application/octet-stream;base64,)" +
                               base64(bin) + R"("}]
  })");
}

TEST(AssetsFeatures, InstancesStripsSparseAndMirroring) {
  testing::ScratchDir dir;
  testing::write_text(dir / "features.gltf", features_document().dump());
  const Model model = load_model(dir / "features.gltf");
  ASSERT_EQ(model.primitives.size(), 3u);
  EXPECT_EQ(model.primitives[0].triangle_count(), 2u);               // strip of 4 -> 2 triangles
  EXPECT_FLOAT_EQ(model.primitives[0].texcoords.at(0)(2, 1), 1.0f);  // normalized ushort
  EXPECT_FLOAT_EQ(model.primitives[2].positions(2, 2), 0.5f);        // sparse substitution
  EXPECT_NEAR(model.bounds.min().x(), -1.0, 1e-12);                  // mirrored instance
  EXPECT_NEAR(model.bounds.max().z(), 5.5, 1e-6);                    // node matrix
  EXPECT_EQ(model.report.weld.topology.components, 3u);
  // Every deform triangle of the two quads faces +z, the mirrored one included.
  for (Eigen::Index f = 0; f < model.deform_mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = model.deform_mesh.V.row(model.deform_mesh.F(f, 0));
    const Eigen::Vector3d b = model.deform_mesh.V.row(model.deform_mesh.F(f, 1));
    const Eigen::Vector3d c = model.deform_mesh.V.row(model.deform_mesh.F(f, 2));
    if (std::abs(a.z()) < 1e-9 && std::abs(b.z()) < 1e-9 && std::abs(c.z()) < 1e-9) {
      EXPECT_GT((b - a).cross(c - a).z(), 0.0) << f;
    }
  }
  Eigen::MatrixXd V = model.deform_mesh.V;
  V.col(2).array() += 0.25;
  write_glb(model, V, dir / "features.glb");
  EXPECT_TRUE(testing::validates_with_zero_errors(dir / "features.glb"));
  const Model again = load_model(dir / "features.glb");
  EXPECT_NEAR(again.bounds.min().x(), -1.0, 1e-6);
  EXPECT_NEAR(again.bounds.max().z(), 5.75, 1e-5);
}

TEST(AssetsFeatures, EmbeddedOnlyModelLoadsFromMemoryWithoutAFolder) {
  const std::string text = features_document().dump();
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  const Model model = load_model_from_memory(bytes, "memory.gltf", {});
  EXPECT_EQ(model.primitives.size(), 3u);
}

}  // namespace
}  // namespace pushpull::assets
