// What `pushpull deform` and `render` print: each warning once, the tolerance that stopped the solver
// and its default, the benchmark's view count.
#include "command_runner.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

using pushpull::testing::CommandResult;
using pushpull::testing::run_pushpull;

const fs::path kHemisphere = fs::path(PUSHPULL_SHARED_DATA) / "meshes" / "hemisphere.off";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class CliMessages : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pushpull_cli_messages_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::string path(const std::string& leaf) const { return (dir_ / leaf).string(); }
  fs::path dir_;
};

TEST_F(CliMessages, HandleNearTheFixedBorderIsWarnedOnce) {
  // Handle: the cap z > 0.9; fixed: everything below z = 0.87, two or three rings away.
  const pd::Mesh mesh = pd::read_mesh(kHemisphere);
  std::ofstream handle(path("handle.txt")), fixed(path("fixed.txt"));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    if (mesh.V(i, 2) > 0.9) handle << i << "\n";
    if (mesh.V(i, 2) < 0.87) fixed << i << "\n";
  }
  handle.close();
  fixed.close();
  const CommandResult run = run_pushpull(
      "deform " + kHemisphere.string() + " --handle " + path("handle.txt") + " --fixed " + path("fixed.txt") +
      " --displacement 0 0 0.1 --out " + path("o.off") + " --metrics " + path("m.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(count(run.output, "handle vertices lie within"), 1u) << run.output;
  std::ifstream in(path("m.json"));
  const nlohmann::json metrics = nlohmann::json::parse(in);
  std::size_t in_json = 0;
  for (const auto& warning : metrics["warnings"])
    in_json += count(warning.get<std::string>(), "handle vertices lie within");
  EXPECT_EQ(in_json, 1u) << metrics["warnings"].dump(2);
}

TEST_F(CliMessages, EnergyToleranceDefaultIsInTheHelpAndInTheStopReason) {
  const CommandResult help = run_pushpull("deform --help");
  ASSERT_EQ(help.status, 0) << help.output;
  EXPECT_NE(help.output.find("(default: 1e-06"), std::string::npos) << help.output;
  // A move tolerance too small to reach: the default energy tolerance stops the solver, and says so.
  const CommandResult run =
      run_pushpull("deform " + kHemisphere.string() +
                   " --handle-at 0 0 1 --handle-radius 0.2 --roi-radius 0.8 --displacement 0 "
                   "0 0.1 --tolerance 1e-9 --iterations 500 --out " +
                   path("o.off") + " --metrics " + path("m.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("energy-tolerance 1e-06, the default"), std::string::npos) << run.output;
  const CommandResult set =
      run_pushpull("deform " + kHemisphere.string() +
                   " --handle-at 0 0 1 --handle-radius 0.2 --roi-radius 0.8 --displacement 0 "
                   "0 0.1 --tolerance 1e-9 --energy-tolerance 1e-5 --iterations 500 --out " +
                   path("o.off") + " --metrics " + path("m.json"));
  ASSERT_EQ(set.status, 0) << set.output;
  EXPECT_NE(set.output.find("(energy-tolerance 1e-05)"), std::string::npos) << set.output;
}

TEST_F(CliMessages, BenchmarkOfOneViewDoesNotSayStereo) {
  const CommandResult mono =
      run_pushpull("render " + kHemisphere.string() + " --size 32 24 --benchmark 1 --out " + path("a.png"));
  ASSERT_EQ(mono.status, 0) << mono.output;
  EXPECT_EQ(mono.output.find("stereo"), std::string::npos) << mono.output;
  EXPECT_NE(mono.output.find("frame time, 1 view"), std::string::npos) << mono.output;
  const CommandResult stereo = run_pushpull(
      "render " + kHemisphere.string() + " --size 32 24 --stereo 0.064 --benchmark 1 --out " + path("b.png"));
  ASSERT_EQ(stereo.status, 0) << stereo.output;
  EXPECT_NE(stereo.output.find("frame time, stereo"), std::string::npos) << stereo.output;
}

}  // namespace
