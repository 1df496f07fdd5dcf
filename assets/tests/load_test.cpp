// Loading the shared test assets: every model loads, welds as documented, Draco matches its twin.
#include "test_support.hpp"

#include <pushpull/assets/info.hpp>
#include <pushpull/assets/model.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <unordered_map>

namespace pushpull::assets {
namespace {

using testing::gltf_data;

TEST(AssetsLoad, EveryModelInSharedDataLoads) {
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(gltf_data())) {
    if (!entry.is_regular_file() || !is_supported_model_path(entry.path())) continue;
    SCOPED_TRACE(entry.path().string());
    const Model model = load_model(entry.path());
    EXPECT_GT(model.deform_mesh.V.rows(), 0);
    EXPECT_GT(model.deform_mesh.F.rows(), 0);
    EXPECT_FALSE(model.primitives.empty());
    for (const Primitive& p : model.primitives) {
      ASSERT_EQ(p.deform_vertex.size(), static_cast<std::size_t>(p.positions.rows()));
      for (std::uint32_t i : p.indices) ASSERT_GE(p.deform_vertex[i], 0);
    }
    ++loaded;
  }
  EXPECT_GE(loaded, 5);
}

TEST(AssetsLoad, CarDrcWelds118PiecesInto9Components) {
  const Model model = load_model(gltf_data() / "car_drc/car.drc");
  EXPECT_EQ(model.report.format, "Draco");
  EXPECT_EQ(model.report.weld.pieces_before, 118u);
  EXPECT_EQ(model.report.weld.topology.components, 9u);
  EXPECT_EQ(model.report.weld.render_vertices, 1856u);
  EXPECT_EQ(model.report.weld.render_triangles, 1744u);
}

// data/README.md says 41 components; welding by position (any tolerance from exact to 1e-5 of the
// diagonal, greedy or transitive) gives 50, and the tolerances that reach 40-44 collapse hundreds
// to thousands of triangles. 50 is what an honest weld of this file gives.
TEST(AssetsLoad, ToyCarWelds2197PiecesInto50ComponentsWithMaterials) {
  const Model model = load_model(gltf_data() / "ToyCar/glTF/ToyCar.gltf");
  EXPECT_EQ(model.report.weld.pieces_before, 2197u);
  EXPECT_EQ(model.report.weld.topology.components, 50u);
  EXPECT_EQ(model.report.weld.collapsed_triangles, 0u);
  EXPECT_EQ(model.report.weld.topology.non_manifold_edges, 0u);
  EXPECT_NEAR(model.bounds.sizes().maxCoeff(), 0.07, 0.02);  // about 7 cm
  EXPECT_FALSE(model.materials.empty());
  EXPECT_FALSE(model.images.empty());
  for (const Image& image : model.images) {
    EXPECT_FALSE(image.missing) << image.name;
    EXPECT_GT(image.width, 0);
  }
  // Its KHR_materials_* / KHR_texture_transform extensions are named as unsupported.
  EXPECT_FALSE(model.report.unsupported_extensions.empty());
  const std::string info = describe_model(model);
  EXPECT_NE(info.find("KHR_materials_clearcoat"), std::string::npos);
}

// The parts the weld made one surface are listed: on the real car the body joins the headlamp reflectors
// and half of each low-beam lens (they share its vertices), which a pull then deforms with the body whatever
// --no-attached-parts says; a user asked why the lamps still moved.
TEST(AssetsLoad, InfoListsThePartsTheWeldJoined) {
  const Model car = load_model(gltf_data() / "AsamVehicle/vehicle_example.gltf");
  const std::string info = describe_model(car);
  const std::size_t joined = info.find("joined:");
  ASSERT_NE(joined, std::string::npos) << info;
  const std::string body = info.substr(joined, info.find('\n', info.find("component 0", joined)) - joined);
  EXPECT_NE(body.find("component 0 ("), std::string::npos) << body;
  EXPECT_NE(body.find("Body"), std::string::npos) << body;
  EXPECT_NE(body.find("Light_Low_Beam_Reflector_FL"), std::string::npos) << body;
  EXPECT_NE(body.find("Light_Low_Beam_Lens_FL (192 of its 384 vertices)"), std::string::npos) << body;
  // Vertices no triangle uses are said (they were left out without a word: 4,943 in the file, 4,941 listed).
  const std::string off = "OFF\n5 1 0\n0 0 0\n1 0 0\n0 1 0\n5 5 5\n6 6 6\n3 0 1 2\n";
  const std::string lone = describe_model(
      load_model_from_memory(std::vector<std::uint8_t>(off.begin(), off.end()), "lone.off", {}));
  EXPECT_NE(lone.find("unused:       2 vertices of the file are used by no triangle"), std::string::npos)
      << lone;
  // A file of one part joins nothing.
  EXPECT_EQ(describe_model(load_model(gltf_data() / "Box_Draco/Box_Draco.glb")).find("joined:"),
            std::string::npos);
}

TEST(AssetsLoad, TargetLengthSetsLifeSizeScaleWithoutTouchingCoordinates) {
  LoadOptions options;
  options.target_length_m = 4.2;
  const Model scaled = load_model(gltf_data() / "ToyCar/glTF/ToyCar.gltf", options);
  const Model plain = load_model(gltf_data() / "ToyCar/glTF/ToyCar.gltf");
  EXPECT_NEAR(scaled.bounds.sizes().maxCoeff() * scaled.scale, 4.2, 1e-9);
  EXPECT_TRUE(scaled.deform_mesh.V.isApprox(plain.deform_mesh.V));
  LoadOptions bad;
  bad.scale = -1.0;
  EXPECT_THROW((void)load_model(gltf_data() / "ToyCar/glTF/ToyCar.gltf", bad), AssetError);
}

TEST(AssetsLoad, WeldToleranceIsRelativeAndSettable) {
  LoadOptions exact;
  exact.weld.relative_tolerance = 0.0;
  const Model unwelded = load_model(gltf_data() / "car_drc/car.drc", exact);
  const Model welded = load_model(gltf_data() / "car_drc/car.drc");
  EXPECT_GE(unwelded.report.weld.topology.components, welded.report.weld.topology.components);
  EXPECT_GT(welded.report.weld.tolerance, 0.0);
  EXPECT_EQ(unwelded.report.weld.tolerance, 0.0);
}

// Largest distance from a vertex of `a` to the nearest vertex of `b` (brute force over a grid).
double one_sided_vertex_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double nearest = (b.rowwise() - a.row(i)).rowwise().squaredNorm().minCoeff();
    worst = std::max(worst, std::sqrt(nearest));
  }
  return worst;
}

TEST(AssetsLoad, DracoTruckHasTheSameShapeAsItsUncompressedTwin) {
  const Model draco = load_model(gltf_data() / "CesiumMilkTruck/glTF-Draco/CesiumMilkTruck.gltf");
  const Model plain = load_model(gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
  const double diagonal = plain.bounds.diagonal().norm();
  EXPECT_LT((draco.bounds.min() - plain.bounds.min()).norm(), 1e-3 * diagonal);
  EXPECT_LT((draco.bounds.max() - plain.bounds.max()).norm(), 1e-3 * diagonal);
  EXPECT_LT(one_sided_vertex_distance(draco.deform_mesh.V, plain.deform_mesh.V), 2e-3 * diagonal);
  EXPECT_LT(one_sided_vertex_distance(plain.deform_mesh.V, draco.deform_mesh.V), 2e-3 * diagonal);
  EXPECT_EQ(draco.primitives.size(), plain.primitives.size());
  EXPECT_EQ(draco.materials.size(), plain.materials.size());
  ASSERT_EQ(draco.images.size(), 1u);  // CesiumMilkTruck.jpg, read from the header only
  EXPECT_EQ(draco.images[0].mime_type, "image/jpeg");
  EXPECT_GT(draco.images[0].width, 0);
  EXPECT_GT(draco.images[0].height, 0);
}

TEST(AssetsLoad, InstancedMeshesGiveOnePrimitivePerNode) {
  // The truck's wheels are one mesh used by two nodes.
  const Model model = load_model(gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
  std::unordered_map<int, int> uses;
  for (const Primitive& p : model.primitives) ++uses[p.mesh];
  EXPECT_TRUE(std::any_of(uses.begin(), uses.end(), [](const auto& u) { return u.second > 1; }));
}

// A mesh file in large coordinates (a 1 cm grid of 1 mm cells 5,000 km from the origin, as site coordinates
// put it) welds on the reader's doubles, its tolerance from their bounding box: as floats (0.5 m apart there)
// every vertex merged into a few and every triangle collapsed.
TEST(AssetsLoad, AMeshFileFarFromTheOriginKeepsEveryVertex) {
  const int n = 11;
  // One more vertex: a copy of vertex 0 moved 1e-9 m (within the weld's 1e-5 of the 1.4 cm diagonal), used in
  // vertex 0's place by the first cell's second triangle; welded into vertex 0, as near the origin.
  std::string off =
      "OFF\n" + std::to_string(n * n + 1) + " " + std::to_string(2 * (n - 1) * (n - 1)) + " 0\n";
  char line[128];
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      std::snprintf(line, sizeof line, "%.4f %.4f 0.25\n", 5e5 + 1e-3 * i, 5e6 + 1e-3 * j);
      off += line;
    }
  std::snprintf(line, sizeof line, "%.9f %.4f 0.25\n", 5e5 + 1e-9, 5e6);
  off += line;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
      off += "3 " + std::to_string(a == 0 ? n * n : a) + " " + std::to_string(d) + " " + std::to_string(c) +
             "\n";
    }
  const Model model =
      load_model_from_memory(std::vector<std::uint8_t>(off.begin(), off.end()), "site.off", {});
  ASSERT_EQ(model.deform_mesh.V.rows(), n * n);
  EXPECT_EQ(model.deform_mesh.F.rows(), 2 * (n - 1) * (n - 1));
  EXPECT_EQ(model.primitives.front().deform_vertex[static_cast<std::size_t>(n * n)], 0);
  EXPECT_EQ(model.primitives.front().deform_vertex[static_cast<std::size_t>(n * n)], 0);
  EXPECT_EQ(model.report.weld.collapsed_triangles, 0u);
  EXPECT_EQ(model.report.weld.topology.components, 1u);
  for (int v = 0; v < n * n; ++v) {  // the reader's doubles, in the file's order
    EXPECT_NEAR(model.deform_mesh.V(v, 0), 5e5 + 1e-3 * (v % n), 1e-9) << "vertex " << v;
    EXPECT_NEAR(model.deform_mesh.V(v, 1), 5e6 + 1e-3 * (v / n), 1e-9) << "vertex " << v;
  }
}

TEST(AssetsLoad, UnsupportedFormatIsRefused) {
  EXPECT_THROW((void)load_model("model.fbx"), AssetError);
  EXPECT_THROW((void)load_model(gltf_data() / "does-not-exist.glb"), AssetError);
}

}  // namespace
}  // namespace pushpull::assets
