// Writing GLB: round trips, deformation through the weld map, atomic replacement, validation.
#include "test_support.hpp"

#include <pushpull/assets/model.hpp>
#include <pushpull/assets/write.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::assets {
namespace {

using testing::gltf_data;
using testing::ScratchDir;

// A smooth bump: vertices near the top of the bounding box move up by 10% of the height.
Eigen::MatrixXd bumped(const Model& model) {
  Eigen::MatrixXd V = model.deform_mesh.V;
  const Eigen::Vector3d centre = model.bounds.center();
  const double radius = 0.3 * model.bounds.diagonal().norm();
  const double height = 0.1 * model.bounds.sizes().y();
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double r = (V.row(v).transpose() - centre).norm() / radius;
    V(v, 1) += height * std::exp(-r * r);
  }
  return V;
}

TEST(AssetsWrite, RoundTripKeepsShapeCountsAndMaterials) {
  ScratchDir dir;
  for (const char* name :
       {"Box_Draco/Box_Draco.glb", "CesiumMilkTruck/glTF-Draco/CesiumMilkTruck.gltf", "car_drc/car.drc"}) {
    SCOPED_TRACE(name);
    const Model model = load_model(gltf_data() / name);
    const auto out = dir / "out.glb";
    write_glb(model, model.deform_mesh.V, out);
    const Model again = load_model(out);
    EXPECT_EQ(again.deform_mesh.V.rows(), model.deform_mesh.V.rows());
    EXPECT_EQ(again.deform_mesh.F.rows(), model.deform_mesh.F.rows());
    EXPECT_EQ(again.materials.size(), model.materials.size());
    EXPECT_EQ(again.images.size(), model.images.size());
    EXPECT_EQ(again.primitives.size(), model.primitives.size());
    EXPECT_LT((again.bounds.min() - model.bounds.min()).norm(), 1e-5 * model.bounds.diagonal().norm());
    EXPECT_TRUE(testing::validates_with_zero_errors(out));
  }
}

TEST(AssetsWrite, DeformedPositionsGoThroughTheWeldMap) {
  ScratchDir dir;
  const Model model = load_model(gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
  const Eigen::MatrixXd V = bumped(model);
  const auto out = dir / "bumped.glb";
  write_glb(model, V, out);
  const Model again = load_model(out);
  ASSERT_EQ(again.deform_mesh.V.rows(), V.rows());
  // Same welding order, so the rows correspond.
  EXPECT_LT((again.deform_mesh.V - V).cwiseAbs().maxCoeff(), 1e-4 * model.bounds.diagonal().norm());
  for (const Primitive& p : again.primitives)
    for (Eigen::Index v = 0; v < p.normals.rows(); ++v) ASSERT_NEAR(p.normals.row(v).norm(), 1.0f, 1e-4f);
  EXPECT_TRUE(testing::validates_with_zero_errors(out));
}

TEST(AssetsWrite, ToyCarLoadDeformWriteValidates) {
  ScratchDir dir;
  const Model model = load_model(gltf_data() / "ToyCar/glTF/ToyCar.gltf");
  const auto out = dir / "toycar.glb";
  const auto warnings = write_glb(model, bumped(model), out);
  const Model again = load_model(out);
  EXPECT_EQ(again.images.size(), model.images.size());
  EXPECT_EQ(again.materials.size(), model.materials.size());
  EXPECT_EQ(again.report.weld.topology.components, model.report.weld.topology.components);
  // The material extensions are carried through.
  EXPECT_EQ(again.report.extensions_used.size(), model.report.extensions_used.size());
  EXPECT_TRUE(testing::validates_with_zero_errors(out));
}

TEST(AssetsWrite, DracoRecompressionRoundTripsAndValidates) {
  ScratchDir dir;
  const Model model = load_model(gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
  const auto out = dir / "truck-draco.glb";
  WriteOptions options;
  options.draco = true;
  write_glb(model, model.deform_mesh.V, out, options);
  EXPECT_LT(std::filesystem::file_size(out),
            std::filesystem::file_size(gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb"));
  const Model again = load_model(out);
  EXPECT_LT((again.bounds.max() - model.bounds.max()).norm(), 1e-3 * model.bounds.diagonal().norm());
  EXPECT_EQ(again.report.weld.render_triangles, model.report.weld.render_triangles);
  EXPECT_TRUE(testing::validates_with_zero_errors(out));
}

TEST(AssetsWrite, FailedWriteLeavesThePreviousFileIntact) {
  ScratchDir dir;
  const Model model = load_model(gltf_data() / "Box_Draco/Box_Draco.glb");
  const auto out = dir / "box.glb";
  write_glb(model, model.deform_mesh.V, out);
  const auto good = testing::read_bytes(out);
  // Wrong shape and non-finite positions are refused before anything is written.
  EXPECT_THROW(write_glb(model, Eigen::MatrixXd::Zero(3, 3), out), AssetError);
  Eigen::MatrixXd nan = model.deform_mesh.V;
  nan(0, 0) = std::nan("");
  EXPECT_THROW(write_glb(model, nan, out), AssetError);
  EXPECT_EQ(testing::read_bytes(out), good);
  // A folder that cannot be written: error, no temporary file left behind.
  EXPECT_THROW(write_glb(model, model.deform_mesh.V, dir / "no-such-folder" / "x.glb"), AssetError);
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

// What the written file leaves out of the source's meshes is said: a mesh only on a node outside the scene
// shown, a line primitive, morph targets and their weights (each was dropped silently).
TEST(AssetsWrite, ContentTheWrittenFileLeavesOutIsSaid) {
  ScratchDir dir;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::vector<std::uint8_t> bin(44);
  std::memcpy(bin.data(), positions, 36);
  std::memcpy(bin.data() + 36, indices, 8);
  testing::write_bytes(dir / "tri.bin", bin);
  testing::write_text(dir / "model.gltf", R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}, {"nodes": [1]}],
    "nodes": [{"mesh": 0}, {"mesh": 1}],
    "meshes": [
      {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "targets": [{"POSITION": 0}]},
                      {"attributes": {"POSITION": 0}, "mode": 1}],
       "weights": [0.5], "extras": {"k": 1}},
      {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "buffers": [{"byteLength": 44, "uri": "tri.bin"}]
  })");
  const Model model = load_model(dir / "model.gltf");
  const std::vector<std::string> warnings = write_glb(model, model.deform_mesh.V, dir / "out.glb");
  std::string all;
  for (const std::string& w : warnings) all += w + "\n";
  for (const char* said : {"1 node(s) outside the scene shown carry meshes that are not written",
                           "1 line or point primitive(s) are not written",
                           "1 mesh(es) with morph targets are written without them"})
    EXPECT_NE(all.find(said), std::string::npos) << said << "\n" << all;
  EXPECT_NE(testing::read_bytes(dir / "out.glb").size(), 0u);
  const std::vector<std::uint8_t> written = testing::read_bytes(dir / "out.glb");
  const std::string text(written.begin(), written.end());
  EXPECT_NE(text.find("\"extras\":{\"k\":1}"), std::string::npos);  // the mesh's extras are kept
}

TEST(AssetsWrite, ValidatorIsInstalledAndRejectsBrokenFiles) {
  ScratchDir dir;
  testing::write_text(dir / "broken.glb", "glTF not really");
  EXPECT_FALSE(testing::validates_with_zero_errors(dir / "broken.glb"));
}

}  // namespace
}  // namespace pushpull::assets

namespace pushpull::assets {
namespace {

TEST(AssetsWrite, PlainMeshBecomesAValidGlb) {
  testing::ScratchDir dir;
  deform::Mesh mesh;
  mesh.V.resize(4, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  mesh.F.resize(2, 3);
  mesh.F << 0, 1, 2, 0, 2, 3;
  const Model model = model_from_mesh(mesh, "quad");
  EXPECT_EQ(model.report.weld.topology.boundary_loops, 1u);
  Eigen::MatrixXd V = mesh.V;
  V(2, 2) = 0.5;
  write_glb(model, V, dir / "quad.glb");
  const Model again = load_model(dir / "quad.glb");
  EXPECT_NEAR(again.bounds.max().z(), 0.5, 1e-6);
  EXPECT_TRUE(testing::validates_with_zero_errors(dir / "quad.glb"));
}

// A plain mesh far from its file's origin (site coordinates: 1e6 m) keeps its shape through the float
// positions a GLB holds: they are relative to the mesh's centre, which the node's matrix carries in double.
// (Stored as absolute floats, its 10 cm cells came back up to 6 cm off.)
TEST(AssetsWrite, APlainMeshFarFromTheOriginKeepsItsShape) {
  testing::ScratchDir dir;
  deform::Mesh mesh;
  const int n = 11;
  mesh.V.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      mesh.V.row(j * n + i) << 1e6 + 0.1 * i + 1e-4 * j, -2e6 + 0.1 * j, 3e5 + 0.01 * std::sin(double(i * j));
  mesh.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      mesh.F.row(f++) << a, a + 1, a + n;
      mesh.F.row(f++) << a + 1, a + n + 1, a + n;
    }
  const Model model = model_from_mesh(mesh, "far");
  Eigen::MatrixXd V = mesh.V;
  V(60, 2) += 0.05;  // one vertex moved: written rebuilt; the others as stored
  write_glb(model, V, dir / "far.glb");
  const Model again = load_model(dir / "far.glb");
  ASSERT_EQ(again.deform_mesh.V.rows(), V.rows());
  EXPECT_LT((again.deform_mesh.V - V).cwiseAbs().maxCoeff(), 1e-6);  // metres, on a 1 m mesh at 1e6 m
  EXPECT_TRUE(testing::validates_with_zero_errors(dir / "far.glb"));
}

}  // namespace
}  // namespace pushpull::assets
