// `pushpull info` and `pushpull deform` on glTF/GLB/Draco models, end to end (issue 4).
#include <gtest/gtest.h>

#include "command_runner.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace {

namespace fs = std::filesystem;

using CliRun = pushpull::testing::CommandResult;
const auto& run = pushpull::testing::run_pushpull;

fs::path data(const std::string& name) {
  return fs::path(PUSHPULL_SHARED_DATA) / "gltf" / name;
}

class Scratch {
 public:
  Scratch()
      : path_(fs::temp_directory_path() / ("pushpull-assets-cli-" + std::to_string(std::random_device{}()))) {
    fs::create_directories(path_);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

TEST(AssetsCli, InfoToyCar) {
  const CliRun r = run("info '" + data("ToyCar/glTF/ToyCar.gltf").string() + "' --length 4.2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2197 pieces -> 50 components"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("life size: longest side 4.2 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("KHR_materials_clearcoat"), std::string::npos) << r.output;
}

TEST(AssetsCli, InfoCarDrc) {
  const CliRun r = run("info '" + data("car_drc/car.drc").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("118 pieces -> 9 components"), std::string::npos) << r.output;
}

TEST(AssetsCli, InfoRefusesBadFilesWithNonZeroExit) {
  Scratch dir;
  std::ofstream(dir / "escape.gltf")
      << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"../../etc/passwd"}]})";
  CliRun r = run("info '" + (dir / "escape.gltf").string() + "'");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("outside the model's folder"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("escape.gltf"), std::string::npos) << r.output;
  std::ofstream(dir / "broken.glb") << "glTF\x02";
  r = run("info '" + (dir / "broken.glb").string() + "'");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("broken.glb"), std::string::npos) << r.output;
}

TEST(AssetsCli, DeformToyCarWritesAValidGlb) {
  Scratch dir;
  const fs::path out = dir / "toycar-deformed.glb";
  // A point on the roof in model (world) coordinates, before any scale.
  const CliRun r =
      run("deform '" + data("ToyCar/glTF/ToyCar.gltf").string() +
          "' --handle-at 0 0.0126 0 --handle-radius 0.004 --roi-radius 0.02 --displacement 0 0.003 0"
          " --iterations 10 --out '" +
          out.string() + "' --metrics '" + (dir / "metrics.json").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(fs::exists(out));
  const fs::path validator = fs::path(PUSHPULL_SOURCE_DIR) / "tools/gltf-validator/validate.js";
  ASSERT_TRUE(fs::exists(fs::path(PUSHPULL_SOURCE_DIR) / "tools/gltf-validator/node_modules/gltf-validator"))
      << "run npm ci in tools/gltf-validator (scripts/setup does)";
  const pushpull::testing::CommandResult report =
      pushpull::testing::run_command("node '" + validator.string() + "' '" + out.string() + "'");
  EXPECT_EQ(report.status, 0) << report.output;
  const CliRun info = run("info '" + out.string() + "'");
  EXPECT_EQ(info.status, 0) << info.output;
}

}  // namespace

namespace {

// The number written just before `what` in `text` (e.g. "6 degenerate"), -1 when absent.
long number_before(const std::string& text, const std::string& what) {
  const std::size_t at = text.find(what);
  if (at == std::string::npos || at < 2) return -1;
  std::size_t start = at - 1;  // the space before `what`
  while (start > 0 && std::isdigit(static_cast<unsigned char>(text[start - 1]))) --start;
  if (start == at - 1) return -1;
  return std::stol(text.substr(start, at - 1 - start));
}

// One definition of a degenerate triangle: `info` and `deform` count the same faces of the welded car.
TEST(AssetsCli, InfoAndDeformCountTheSameDegenerateTriangles) {
  Scratch dir;
  {
    std::ofstream handle(dir / "handle.txt");
    handle << "0\n";
  }
  std::string model = "'";  // quoted for the shell (appended: GCC 12 warns on "'" + std::string)
  model += data("AsamVehicle/vehicle_example.gltf").string();
  model += "'";
  const CliRun info = run("info " + model);
  ASSERT_EQ(info.status, 0) << info.output;
  const CliRun deform = run("deform " + model + " --handle " + (dir / "handle.txt").string() +
                            " --roi-radius 0.3 --displacement 0 0.01 0 --out " + (dir / "o.glb").string() +
                            " --metrics " + (dir / "m.json").string());
  ASSERT_EQ(deform.status, 0) << deform.output;
  const long in_info = number_before(info.output, "degenerate triangles");
  const long in_deform = number_before(deform.output, "degenerate faces");
  EXPECT_EQ(in_info, 6) << info.output;  // six zero-area slivers on the body
  EXPECT_EQ(in_info, in_deform) << info.output << "\n" << deform.output;
  // What the weld collapsed (and dropped) is reported apart from them.
  EXPECT_EQ(number_before(info.output, "triangles collapsed by the weld or repeating a corner"), 12)
      << info.output;
}

}  // namespace
