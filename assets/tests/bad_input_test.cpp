// Untrusted input (issue 4, item 5): every kind of bad file gets a clear error or warning.
#include "test_support.hpp"

#include "../src/uri_policy.hpp"

#include <pushpull/assets/model.hpp>

#include <nlohmann/json.hpp>

#include <cstring>

namespace pushpull::assets {
namespace {

using nlohmann::json;
using testing::ScratchDir;

// A one-triangle glTF whose buffer is tri.bin beside it.
std::vector<std::uint8_t> triangle_bin() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::vector<std::uint8_t> bytes(44);
  std::memcpy(bytes.data(), positions, 36);
  std::memcpy(bytes.data() + 36, indices, 8);
  return bytes;
}

json triangle_gltf(const std::string& buffer_uri = "tri.bin") {
  return json::parse(R"({
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "buffers": [{"byteLength": 44, "uri": ")" +
                     buffer_uri + R"("}]
  })");
}

// Writes `document` as model.gltf (+ tri.bin) in `dir` and loads it.
Model load_document(const ScratchDir& dir, const json& document) {
  testing::write_bytes(dir / "tri.bin", triangle_bin());
  testing::write_text(dir / "model.gltf", document.dump());
  return load_model(dir / "model.gltf");
}

// Expects load to throw AssetError whose message contains `needle` (and names the file).
void expect_refused(const ScratchDir& dir, const json& document, const std::string& needle) {
  try {
    (void)load_document(dir, document);
    ADD_FAILURE() << "loaded without error, expected: " << needle;
  } catch (const AssetError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(needle), std::string::npos) << message;
    EXPECT_NE(message.find("model.gltf"), std::string::npos) << message;
  }
}

TEST(AssetsBadInput, ValidTriangleLoads) {
  ScratchDir dir;
  const Model model = load_document(dir, triangle_gltf());
  EXPECT_EQ(model.deform_mesh.F.rows(), 1);
  EXPECT_EQ(model.report.weld.topology.boundary_loops, 1u);
}

// A model whose every triangle has zero area in the file (a node scaled to zero; coincident points) is named
// as degenerate, not as collapsed by a weld tolerance "too large"; the load also lists the files it read.
TEST(AssetsBadInput, AModelOfZeroAreaTrianglesIsNamedDegenerate) {
  ScratchDir dir;
  json flat = triangle_gltf();
  flat["nodes"][0]["scale"] = {0, 0, 0};
  expect_refused(dir, flat, "every triangle (1) has zero area in the file itself");
  try {
    (void)load_model_from_memory(
        std::vector<std::uint8_t>{'O', 'F', 'F', '\n', '3', ' ', '1', ' ', '0', '\n', '1', ' ',
                                  '1', ' ', '1', '\n', '1', ' ', '1', ' ', '1', '\n', '1', ' ',
                                  '1', ' ', '1', '\n', '3', ' ', '0', ' ', '1', ' ',  '2', '\n'},
        "same.off", {});
    ADD_FAILURE() << "three coincident points loaded";
  } catch (const AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("same.off: every triangle (1) has zero area"), std::string::npos)
        << e.what();
  }
  // A coordinate beyond the 32-bit floats the model is drawn in: named with its vertex.
  const std::string far_text = "OFF\n3 1 0\n0 0 0\n1e150 0 0\n0 1 0\n3 0 1 2\n";
  try {
    (void)load_model_from_memory(std::vector<std::uint8_t>(far_text.begin(), far_text.end()), "far.off", {});
    ADD_FAILURE() << "1e150 loaded";
  } catch (const AssetError& e) {
    EXPECT_NE(
        std::string(e.what()).find("far.off: vertex 1 has the coordinate 1e+150, beyond the 32-bit floats"),
        std::string::npos)
        << e.what();
  }
  const Model model = load_document(dir, triangle_gltf());
  ASSERT_EQ(model.source_files.size(), 2u);
  EXPECT_EQ(model.source_files[0], dir / "model.gltf");
  EXPECT_EQ(model.source_files[1].filename(), "tri.bin");
}

// JSON that is not glTF 2.0 (no "asset") and a "scene" naming none of the scenes are refused by name
// (tinygltf said "JSON string too short." of the first; the second showed scene 0 silently).
TEST(AssetsBadInput, NoAssetAndAMissingSceneAreNamed) {
  ScratchDir dir;
  expect_refused(dir, json::object(), "not a glTF 2.0 file: no \"asset\" object");
  json no_version = triangle_gltf();
  no_version["asset"].erase("version");
  expect_refused(dir, no_version, "not a glTF 2.0 file");
  json far = triangle_gltf();
  far["scene"] = 3;
  expect_refused(dir, far, "\"scene\" 3 names none of its 1 scene(s)");
  json negative = triangle_gltf();
  negative["scene"] = -1;
  expect_refused(dir, negative, "\"scene\" -1 names none");
  // glTF 1.0 is another format (it was read as 2.0).
  json old = triangle_gltf();
  old["asset"]["version"] = "1.0";
  expect_refused(dir, old, "glTF version \"1.0\": only glTF 2.x is read");
}

// A required extension that may change the geometry and that pushpull does not interpret is refused (it was
// only warned of, and the model loaded without it); one that changes only the look is warned of and loads.
TEST(AssetsBadInput, ARequiredExtensionThatMayChangeTheGeometryIsRefused) {
  ScratchDir dir;
  for (const char* extension : {"KHR_foo", "EXT_mesh_gpu_instancing"}) {
    json document = triangle_gltf();
    document["extensionsUsed"] = {extension};
    document["extensionsRequired"] = {extension};
    expect_refused(dir, document,
                   std::string("requires extension ") + extension + ", which pushpull does not support");
  }
  // `pushpull info` loads it to report it, with the warning.
  json unknown = triangle_gltf();
  unknown["extensionsUsed"] = {"KHR_foo"};
  unknown["extensionsRequired"] = {"KHR_foo"};
  testing::write_text(dir / "unknown.gltf", unknown.dump());
  LoadOptions reporting;
  reporting.refuse_unsupported_required = false;
  const Model reported = load_model(dir / "unknown.gltf", reporting);
  ASSERT_EQ(reported.report.warnings.size(), 1u);
  EXPECT_NE(reported.report.warnings[0].find("KHR_foo (required) may change the geometry"), std::string::npos)
      << reported.report.warnings[0];
  json looks = triangle_gltf();
  looks["extensionsUsed"] = {"KHR_texture_transform", "KHR_foo"};
  looks["extensionsRequired"] = {"KHR_texture_transform"};
  const Model model = load_document(dir, looks);
  EXPECT_EQ(model.deform_mesh.F.rows(), 1);
  ASSERT_EQ(model.report.warnings.size(), 2u);
  EXPECT_NE(model.report.warnings[0].find("KHR_texture_transform (required) is not supported"),
            std::string::npos)
      << model.report.warnings[0];
}

// Positions that are not floats without KHR_mesh_quantization (unsigned integers were read as metres, a model
// 1e9 long), and a node transform that puts the vertices beyond the 32-bit floats they are drawn in (drawn as
// nothing, solved into non-finite positions), are refused by name.
TEST(AssetsBadInput, PositionsThatAreNotFloatsOrOutOfRangeAreNamed) {
  ScratchDir dir;
  json integers = triangle_gltf();
  integers["accessors"][0]["componentType"] = 5125;
  expect_refused(dir, integers, "POSITION accessor 0 is not of floats (componentType 5125");
  json far = triangle_gltf();
  far["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e308, 0, 0, 1};
  expect_refused(dir, far, "has the coordinate 1e+308 in the model frame (its node's transform applied)");
}

TEST(AssetsBadInput, UriPolicy) {
  using detail::uri_problem;
  EXPECT_EQ(uri_problem("tri.bin"), "");
  EXPECT_EQ(uri_problem("sub/dir/tri.bin"), "");
  EXPECT_EQ(uri_problem("sub/../tri.bin"), "");
  EXPECT_EQ(uri_problem("data:application/octet-stream;base64,AAAA"), "");
  EXPECT_NE(uri_problem("../tri.bin"), "");
  EXPECT_NE(uri_problem("sub/../../tri.bin"), "");
  EXPECT_NE(uri_problem("%2e%2e/tri.bin"), "");
  EXPECT_NE(uri_problem("/etc/passwd"), "");
  EXPECT_NE(uri_problem("\\\\server\\share\\x.bin"), "");
  EXPECT_NE(uri_problem("C:/x.bin"), "");
  EXPECT_NE(uri_problem("file:///etc/passwd"), "");
  EXPECT_NE(uri_problem("http://example.com/x.bin"), "");
  EXPECT_NE(uri_problem("tri%00.bin"), "");
  EXPECT_NE(uri_problem("tri%zz.bin"), "");
}

// A data: URI that is not base64 is refused; the message quotes its start and length, not megabytes of it.
TEST(AssetsBadInput, AnUndecodableDataUriIsQuotedShort) {
  const ScratchDir dir;
  const std::string payload(100000, '!');
  try {
    (void)load_document(dir, triangle_gltf("data:application/octet-stream;base64," + payload));
    ADD_FAILURE() << "accepted";
  } catch (const AssetError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("model.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("(100000 characters)"), std::string::npos) << message;
    EXPECT_LT(message.size(), 300u) << message;
  }
}

TEST(AssetsBadInput, BufferUriOutsideTheFolderIsRefused) {
  ScratchDir dir;
  expect_refused(dir, triangle_gltf("../tri.bin"), "outside the model's folder");
  expect_refused(dir, triangle_gltf("/etc/passwd"), "absolute paths are not allowed");
  expect_refused(dir, triangle_gltf("https://example.com/tri.bin"), "scheme");
  expect_refused(dir, triangle_gltf("file:///tmp/tri.bin"), "scheme");
}

TEST(AssetsBadInput, SymlinkEscapingTheFolderIsRefused) {
  ScratchDir outside;
  ScratchDir dir;
  testing::write_bytes(outside / "secret.bin", triangle_bin());
  std::filesystem::create_symlink(outside / "secret.bin", dir / "link.bin");
  testing::write_text(dir / "model.gltf", triangle_gltf("link.bin").dump());
  try {
    (void)load_model(dir / "model.gltf");
    ADD_FAILURE() << "symlink escape loaded";
  } catch (const AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("outside"), std::string::npos) << e.what();
  }
}

TEST(AssetsBadInput, ImageUriOutsideTheFolderIsRefused) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["images"] = json::array({{{"uri", "../../texture.png"}}});
  expect_refused(dir, document, "image 0");
}

TEST(AssetsBadInput, MissingImageIsAWarning) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["images"] = json::array({{{"uri", "missing.png"}}});
  document["textures"] = json::array({{{"source", 0}}});
  document["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  document["meshes"][0]["primitives"][0]["material"] = 0;
  const Model model = load_document(dir, document);
  ASSERT_EQ(model.images.size(), 1u);
  EXPECT_TRUE(model.images[0].missing);
  EXPECT_TRUE(std::any_of(model.report.warnings.begin(), model.report.warnings.end(),
                          [](const std::string& w) { return w.find("missing") != std::string::npos; }));
}

TEST(AssetsBadInput, MalformedJsonIsRefused) {
  ScratchDir dir;
  testing::write_text(dir / "model.gltf", R"({"asset": {"version": "2.0"}, "meshes": [)");
  EXPECT_THROW((void)load_model(dir / "model.gltf"), AssetError);
  testing::write_text(dir / "model.gltf", std::string(10000, '[') + std::string(10000, ']'));
  try {
    (void)load_model(dir / "model.gltf");
    ADD_FAILURE();
  } catch (const AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("nested"), std::string::npos) << e.what();
  }
  testing::write_text(dir / "model.gltf", R"({"asset": {"version": "2.0"}, "meshes": 7})");
  EXPECT_THROW((void)load_model(dir / "model.gltf"), AssetError);
  testing::write_text(dir / "model.gltf", "");
  EXPECT_THROW((void)load_model(dir / "model.gltf"), AssetError);
}

// A .glb that is not one (empty, a few bytes, glTF JSON renamed) is named as such, not as "malformed JSON".
TEST(AssetsBadInput, AGlbThatIsNotOneIsNamedSo) {
  ScratchDir dir;
  for (const std::string& text :
       {std::string(), std::string("x"), std::string(R"({"asset":{"version":"2.0"}})")}) {
    testing::write_text(dir / "model.GLB", text);
    try {
      (void)load_model(dir / "model.GLB");
      ADD_FAILURE() << "loaded";
    } catch (const AssetError& e) {
      EXPECT_NE(
          std::string(e.what()).find("model.GLB: not a GLB file (" + std::to_string(text.size()) + " bytes"),
          std::string::npos)
          << e.what();
    }
  }
}

TEST(AssetsBadInput, TruncatedBufferIsRefused) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["buffers"][0]["byteLength"] = 4000;  // the file has 44 bytes
  expect_refused(dir, document, "model.gltf");
}

TEST(AssetsBadInput, CorruptBufferViewIsNotCalledTruncated) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["bufferViews"][0]["byteLength"] = 4000;  // the buffer (complete) has 44 bytes
  expect_refused(dir, document, "bufferView 0 (byteOffset 0, byteLength 4000) runs past the end of buffer 0");
  try {
    (void)load_document(dir, document);
  } catch (const AssetError& e) {
    EXPECT_EQ(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(AssetsBadInput, OversizedExternalFileIsRefused) {
  ScratchDir dir;
  testing::write_bytes(dir / "tri.bin", triangle_bin());
  testing::write_text(dir / "model.gltf", triangle_gltf().dump());
  LoadOptions options;
  options.limits.max_file_bytes = 40;  // the .gltf is larger than this
  EXPECT_THROW((void)load_model(dir / "model.gltf", options), AssetError);
}

TEST(AssetsBadInput, AccessorOutOfRangeIsRefused) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["accessors"][0]["count"] = 300;
  expect_refused(dir, document, "accessor 0");
  document = triangle_gltf();
  document["accessors"][0]["byteOffset"] = 32;
  expect_refused(dir, document, "accessor 0");
  document = triangle_gltf();
  document["bufferViews"][1]["byteLength"] = 400;
  expect_refused(dir, document, "model.gltf");
  document = triangle_gltf();
  document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  expect_refused(dir, document, "model.gltf");
}

TEST(AssetsBadInput, IndexOutOfRangeIsRefused) {
  ScratchDir dir;
  std::vector<std::uint8_t> bin = triangle_bin();
  bin[36 + 4] = 77;  // third index = 77 with 3 vertices
  testing::write_bytes(dir / "tri.bin", bin);
  testing::write_text(dir / "model.gltf", triangle_gltf().dump());
  try {
    (void)load_model(dir / "model.gltf");
    ADD_FAILURE();
  } catch (const AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

TEST(AssetsBadInput, AbsurdCountsAreRefusedWithoutAllocating) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["accessors"][0]["count"] = 4000000000000ull;
  expect_refused(dir, document, "accessor 0");
  document = triangle_gltf();
  document["accessors"][1]["count"] = 4000000000ull;
  expect_refused(dir, document, "accessor 1");
}

TEST(AssetsBadInput, NodeCycleIsRefused) {
  ScratchDir dir;
  json document = triangle_gltf();
  document["nodes"] = json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
  expect_refused(dir, document, "model.gltf");
}

TEST(AssetsBadInput, TruncatedGlbIsRefused) {
  ScratchDir dir;
  std::vector<std::uint8_t> glb = testing::read_bytes(testing::gltf_data() / "Box_Draco/Box_Draco.glb");
  for (std::size_t keep :
       {std::size_t{0}, std::size_t{11}, std::size_t{19}, glb.size() / 2, glb.size() - 1}) {
    testing::write_bytes(dir / "cut.glb",
                         std::vector<std::uint8_t>(glb.begin(), glb.begin() + static_cast<long>(keep)));
    EXPECT_THROW((void)load_model(dir / "cut.glb"), AssetError) << keep;
  }
}

// The message of a refused GLB, "" when it loads.
std::string glb_refusal(const std::vector<std::uint8_t>& bytes) {
  try {
    (void)load_model_from_memory(bytes, "damaged.glb", {});
  } catch (const AssetError& e) {
    return e.what();
  }
  return "";
}

void put_u32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i)
    bytes[offset + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(value >> (8 * i));
}

TEST(AssetsBadInput, DamagedGlbNamesTheActualProblem) {
  const std::vector<std::uint8_t> glb =
      testing::read_bytes(testing::gltf_data() / "CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb");
  ASSERT_GT(glb.size(), 1000u);
  const std::uint32_t json_length =
      static_cast<std::uint32_t>(glb[12]) | static_cast<std::uint32_t>(glb[13]) << 8 |
      static_cast<std::uint32_t>(glb[14]) << 16 | static_cast<std::uint32_t>(glb[15]) << 24;
  const std::size_t bin_header = (20 + json_length + 3) & ~std::size_t{3};

  // A cut file is truncated.
  const std::string cut =
      glb_refusal(std::vector<std::uint8_t>(glb.begin(), glb.begin() + static_cast<long>(glb.size() / 2)));
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;

  // A complete file whose header length field is corrupt is not "truncated".
  std::vector<std::uint8_t> header = glb;
  put_u32(header, 8, static_cast<std::uint32_t>(glb.size() + 1000));
  const std::string bad_header = glb_refusal(header);
  EXPECT_EQ(bad_header.find("truncated"), std::string::npos) << bad_header;
  EXPECT_NE(bad_header.find("corrupt header"), std::string::npos) << bad_header;
  EXPECT_NE(bad_header.find("damaged.glb"), std::string::npos) << bad_header;

  // A complete file whose BIN chunk length field is corrupt is not "truncated" either.
  std::vector<std::uint8_t> chunk = glb;
  put_u32(chunk, bin_header, 100'000'000u);
  const std::string bad_chunk = glb_refusal(chunk);
  EXPECT_EQ(bad_chunk.find("truncated"), std::string::npos) << bad_chunk;
  EXPECT_NE(bad_chunk.find("corrupt BIN chunk header"), std::string::npos) << bad_chunk;
}

TEST(AssetsBadInput, CorruptedDracoIsRefused) {
  ScratchDir dir;
  std::vector<std::uint8_t> drc = testing::read_bytes(testing::gltf_data() / "car_drc/car.drc");
  testing::write_bytes(dir / "cut.drc", std::vector<std::uint8_t>(
                                            drc.begin(), drc.begin() + static_cast<long>(drc.size() / 3)));
  EXPECT_THROW((void)load_model(dir / "cut.drc"), AssetError);
  std::vector<std::uint8_t> garbage = drc;
  for (std::size_t i = 0; i < 64 && i < garbage.size(); ++i) garbage[i] ^= 0x5A;
  testing::write_bytes(dir / "garbage.drc", garbage);
  EXPECT_THROW((void)load_model(dir / "garbage.drc"), AssetError);
  // A Draco payload inside a GLB: flip bytes in the middle of Box_Draco's BIN chunk.
  std::vector<std::uint8_t> glb = testing::read_bytes(testing::gltf_data() / "Box_Draco/Box_Draco.glb");
  const std::size_t from = glb.size() - 100;
  for (std::size_t i = from; i < glb.size(); ++i) glb[i] = static_cast<std::uint8_t>(i * 37);
  testing::write_bytes(dir / "box.glb", glb);
  try {
    const Model model = load_model(dir / "box.glb");
    SUCCEED() << "decoded despite corruption (Draco has no checksum)";
  } catch (const AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("box.glb"), std::string::npos) << e.what();
  }
}

TEST(AssetsBadInput, RandomBytesNeverCrash) {
  std::mt19937 random(4);
  const std::vector<std::uint8_t> seed =
      testing::read_bytes(testing::gltf_data() / "Box_Draco/Box_Draco.glb");
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> bytes = seed;
    for (int k = 0; k < 8; ++k) bytes[random() % bytes.size()] = static_cast<std::uint8_t>(random());
    try {
      (void)load_model_from_memory(bytes, "fuzz.glb", {});
    } catch (const AssetError&) {
    }
  }
}

}  // namespace
}  // namespace pushpull::assets
