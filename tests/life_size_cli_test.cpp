// Life size on every command: `deform` and `render` take --scale S / --length M like `info`; points,
// radii, displacements and camera positions are typed in life-size metres, written models keep the
// file's units, printed lengths are life-size millimetres.
#include "command_runner.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

using pushpull::testing::CommandResult;
using pushpull::testing::run_pushpull;

// The unit hemisphere (radius 1 file unit, longest side 1.99037) read at --scale 0.125: a 25 cm dome.
// A power of two keeps the conversion of typed metres to file units exact, so the runs compare bit for bit.
const fs::path kHemisphere = fs::path(PUSHPULL_SHARED_DATA) / "meshes" / "hemisphere.off";

class LifeSizeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pushpull_life_size_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::string path(const std::string& leaf) const { return (dir_ / leaf).string(); }
  fs::path dir_;
};

std::vector<char> bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(LifeSizeCli, DeformTakesLifeSizeMetresAndWritesFileUnits) {
  const std::string common = " --method arap-sr --tolerance 0 --iterations 5";
  // The same pull in file units and at --scale 0.125 in metres; a --length run for the printed scale.
  const CommandResult file_units =
      run_pushpull("deform " + kHemisphere.string() +
                   " --handle-at 0 0 1 --handle-radius 0.2 --roi-radius 0.8 --displacement 0 0 0.5" + common +
                   " --out " + path("a.off") + " --metrics " + path("a.json"));
  ASSERT_EQ(file_units.status, 0) << file_units.output;
  const CommandResult scaled =
      run_pushpull("deform " + kHemisphere.string() +
                   " --scale 0.125 --handle-at 0 0 0.125 --handle-radius 0.025 --roi-radius 0.1 "
                   "--displacement 0 0 0.0625" +
                   common + " --out " + path("b.off") + " --metrics " + path("b.json"));
  ASSERT_EQ(scaled.status, 0) << scaled.output;
  const CommandResult by_length = run_pushpull(
      "deform " + kHemisphere.string() +
      " --length 0.25 --handle-at 0 0 0.125 --handle-radius 0.025 --roi-radius 0.1 --displacement 0 0 0.05" +
      common + " --out " + path("c.off") + " --metrics " + path("c.json"));
  ASSERT_EQ(by_length.status, 0) << by_length.output;

  // Written models keep the file's units: the same pull gives the same mesh.
  const pd::Mesh a = pd::read_mesh(path("a.off")), b = pd::read_mesh(path("b.off"));
  EXPECT_EQ(a.V, b.V);
  EXPECT_NEAR((a.V - pd::read_mesh(kHemisphere).V).rowwise().norm().maxCoeff(), 0.5, 1e-9);

  // Printed lengths are life-size millimetres; the metrics say which scale was used.
  EXPECT_NE(file_units.output.find("|d| = 500.0 mm"), std::string::npos) << file_units.output;
  EXPECT_NE(file_units.output.find("max displacement 500.00 mm"), std::string::npos) << file_units.output;
  EXPECT_NE(scaled.output.find("|d| = 62.5 mm"), std::string::npos) << scaled.output;
  EXPECT_NE(scaled.output.find("max displacement 62.50 mm"), std::string::npos) << scaled.output;
  EXPECT_NE(scaled.output.find("life size: 0.125 m per file unit"), std::string::npos) << scaled.output;
  EXPECT_NE(by_length.output.find("|d| = 50.0 mm"), std::string::npos) << by_length.output;
  std::ifstream metrics(path("b.json"));
  const nlohmann::json m = nlohmann::json::parse(metrics);
  EXPECT_DOUBLE_EQ(m["life_size_scale"].get<double>(), 0.125);
  EXPECT_NEAR(m["max_displacement"].get<double>(), 0.5, 1e-9);  // JSON lengths in model units
  // --length: the longest side (1.99037 file units) becomes 0.25 m; the pull of 5 cm is 0.398 file units.
  std::ifstream metrics_c(path("c.json"));
  const nlohmann::json mc = nlohmann::json::parse(metrics_c);
  EXPECT_NEAR(mc["life_size_scale"].get<double>(), 0.25 / 1.99037, 1e-6);
  EXPECT_NEAR(pd::read_mesh(path("c.off")).V.col(2).maxCoeff(), 1.0 + 0.05 * 1.99037 / 0.25, 1e-4);

  const CommandResult help = run_pushpull("deform --help");
  EXPECT_NE(help.output.find("--scale"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("--length"), std::string::npos) << help.output;
}

TEST_F(LifeSizeCli, RenderTakesLifeSizeMetres) {
  // Deform once (file units), then draw the result with handle, arrow and camera typed in file units
  // and again at --scale 0.125 in metres: the same picture.
  const CommandResult deform = run_pushpull(
      "deform " + kHemisphere.string() +
      " --handle-at 0 0 1 --handle-radius 0.2 --roi-radius 0.8 --displacement 0.2 0 0.3 --method arap-sr"
      " --tolerance 0 --iterations 3 --out " +
      path("pulled.off") + " --metrics " + path("m.json"));
  ASSERT_EQ(deform.status, 0) << deform.output;
  const std::string common = kHemisphere.string() + " --deformed " + path("pulled.off") +
                             " --color displacement --no-legend --size 96 72 --up 0 0 1";
  const CommandResult file_units = run_pushpull(
      "render " + common +
      " --handle-at 0 0 1 --handle-radius 0.2 --arrow 0 0 1 0.2 0 1.3 --eye 4 -3 2 --target 0 0 0.5"
      " --scalar-max 0.4 --out " +
      path("a.png"));
  ASSERT_EQ(file_units.status, 0) << file_units.output;
  const CommandResult scaled = run_pushpull(
      "render " + common +
      " --scale 0.125 --handle-at 0 0 0.125 --handle-radius 0.025 --arrow 0 0 0.125 0.025 0 0.1625"
      " --eye 0.5 -0.375 0.25 --target 0 0 0.0625 --scalar-max 0.05 --out " +
      path("b.png"));
  ASSERT_EQ(scaled.status, 0) << scaled.output;
  const std::vector<char> a = bytes_of(path("a.png")), b = bytes_of(path("b.png"));
  ASSERT_GT(a.size(), 100u);
  EXPECT_TRUE(a == b) << "the picture changed with the life-size scale";
  // A stereo eye distance is life-size metres too: 8 cm at 12.5 cm per file unit is 0.64 file units.
  const CommandResult stereo_file =
      run_pushpull("render " + common + " --stereo 0.64 --out " + path("s1.png"));
  const CommandResult stereo_scaled =
      run_pushpull("render " + common + " --scale 0.125 --stereo 0.08 --out " + path("s2.png"));
  ASSERT_EQ(stereo_file.status, 0) << stereo_file.output;
  ASSERT_EQ(stereo_scaled.status, 0) << stereo_scaled.output;
  EXPECT_TRUE(bytes_of(path("s1.png")) == bytes_of(path("s2.png")));
}

}  // namespace
