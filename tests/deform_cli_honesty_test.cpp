// "Converged" holds for what `pushpull deform` writes, not only for the solver's region: the separate parts
// that follow the surface (lamps, trims; pushpull/deform/attached_parts.hpp) move with it, and must not turn
// the solve's error into a larger one. The README's ToyCar example, arap-sr: the region stopped 0.40 mm from
// the minimiser (estimate 0.87 mm), but four vertices of a part riding 6 cm above the fine tessellation of
// the car's body were 3.9 mm off (4.4x the estimate), their offsets turned by the rotation of a patch only a
// few millimetres across. The patches now grow as wide as the offsets they carry.
#include "command_runner.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

const fs::path kToyCar = fs::path(PUSHPULL_SHARED_DATA) / "gltf" / "ToyCar" / "glTF" / "ToyCar.gltf";

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Runs `pull` (a deform command line without outputs; |d| = `pull_m` metres at life size) with its defaults
// and with --tolerance `reference_tolerance`, and returns the largest distance of a written vertex (the
// attached parts' too) between the two, over |d|, and the default run's estimate, after checking both
// converged.
struct Honesty {
  double truth = 0.0, estimate = 0.0, tolerance = 0.0;
  int iterations = 0;
};

Honesty measure(const std::string& name, const std::string& pull, double pull_m, double reference_tolerance) {
  const fs::path dir =
      fs::temp_directory_path() / ("pushpull_cli_honesty_" + std::to_string(::getpid()) + "_" + name);
  fs::create_directories(dir);
  Honesty h;
  const auto run = pushpull::testing::run_pushpull(pull + " --out '" + (dir / "default.off").string() +
                                                   "' --metrics '" + (dir / "default.json").string() + "'");
  EXPECT_EQ(run.status, 0) << run.output;
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%g", reference_tolerance);
  const auto reference = pushpull::testing::run_pushpull(
      pull + " --tolerance " + tolerance + " --iterations 20000 --out '" + (dir / "reference.off").string() +
      "' --metrics '" + (dir / "reference.json").string() + "'");
  EXPECT_EQ(reference.status, 0) << reference.output;
  if (run.status != 0 || reference.status != 0) return h;
  const nlohmann::json metrics = read_json(dir / "default.json");
  EXPECT_TRUE(bool(metrics.at("converged")));
  EXPECT_TRUE(bool(read_json(dir / "reference.json").at("converged")));
  int moved_parts = 0;
  for (const nlohmann::json& part : metrics.at("attached_parts").at("parts"))
    moved_parts += part.at("max_displacement").get<double>() > 0.0 ? 1 : 0;
  EXPECT_GT(moved_parts, 0) << run.output;  // parts followed the surface

  const pd::Mesh result = pd::read_mesh(dir / "default.off");
  const pd::Mesh exact = pd::read_mesh(dir / "reference.off");
  EXPECT_EQ(result.V.rows(), exact.V.rows());
  if (result.V.rows() != exact.V.rows()) return h;
  // Every vertex written, the attached parts' too, in metres at life size over |d|.
  const double scale = metrics.at("life_size_scale").get<double>();
  h.truth = (result.V - exact.V).rowwise().norm().maxCoeff() * scale / pull_m;
  h.estimate = metrics.at("error_estimate").get<double>();
  h.tolerance = metrics.at("tolerance").get<double>();
  h.iterations = metrics.at("iterations").get<int>();
  std::printf("%s: %d iterations, estimate %.2e |d|, true %.2e |d|\n", name.c_str(), h.iterations, h.estimate,
              h.truth);
  fs::remove_all(dir);
  return h;
}

TEST(DeformCliHonesty, TheToyCarExampleWithItsAttachedPartsIsWithinTwiceItsEstimate) {
  if (!fs::exists(kToyCar)) GTEST_SKIP() << kToyCar << " is missing";
  const Honesty h = measure("example",
                            "deform '" + kToyCar.string() +
                                "' --length 4.2 --handle-at 0 0.7 0 --handle-radius 0.3 --roi-radius 1"
                                " --displacement 0 0.1 0 --method arap-sr",
                            0.1, 1e-9);
  EXPECT_LE(h.truth, 2.0 * h.estimate);
  EXPECT_LE(h.truth, 2.0 * h.tolerance);
}

// The ToyCar's front corner pulled 50 mm along the car with asan: the iterates stall 0.019 |d| from the
// minimiser for tens of iterations while their steps shrink, a slow mode (rate 0.9995) the rate probe's 40
// Lanczos steps from a random start did not find (0.99728): it stopped "converged" after 74 iterations with
// an estimate of 6.6e-3 |d|, 2.9x optimistic. The probe now starts along the last step too, where that mode
// lives, and finds it.
TEST(DeformCliHonesty, AStallAtTheToyCarsFrontCornerIsNotTakenForConvergence) {
  if (!fs::exists(kToyCar)) GTEST_SKIP() << kToyCar << " is missing";
  const Honesty h = measure("stall",
                            "deform '" + kToyCar.string() +
                                "' --length 4.2 --handle-at 0.5018 0.3558 0.9661 --handle-radius 0.1"
                                " --roi-radius 0.8 --displacement 0 0 0.05 --method asan",
                            0.05, 1e-7);
  EXPECT_LE(h.truth, 2.0 * h.estimate);
  EXPECT_LE(h.truth, 2.0 * h.tolerance);
}

}  // namespace
