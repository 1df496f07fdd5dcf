// End-to-end runs of `pushpull deform`: a mesh and METRICS.json come out for good input; bad input exits
// non-zero with a message naming the file and the problem.
#include "command_runner.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

namespace {

const fs::path kHemisphere = fs::path(PUSHPULL_SHARED_DATA) / "meshes" / "hemisphere.off";

using RunResult = pushpull::testing::CommandResult;
using pushpull::testing::run_pushpull;

// Two 11 x 11-vertex patches side by side on z = 0, y in [0, 1]: A over x in [0, 1], B over x in [1 + gap,
// 2 + gap]; each writes its own copy of the seam column (tessellated CAD). File vertex j * 11 + i of patch p
// is p * 121 + j * 11 + i.
std::string two_patches_off(double gap) {
  std::string off = "OFF\n242 400 0\n";
  for (int patch = 0; patch < 2; ++patch)
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i)
        off += std::to_string(patch * (1.0 + gap) + 0.1 * i) + " " + std::to_string(0.1 * j) + " 0\n";
  for (int patch = 0; patch < 2; ++patch)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        const int a = patch * 121 + j * 11 + i, b = a + 1, c = a + 11, d = a + 12;
        off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
        off += "3 " + std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
      }
  return off;
}

class DeformCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pushpull_deform_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    // Handle: the cap z > 0.9; fixed: the base ring (the mesh boundary, z < 0.1).
    const pd::Mesh mesh = pd::read_mesh(kHemisphere);
    std::ofstream handle(path("handle.txt")), fixed(path("fixed.txt"));
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      if (mesh.V(i, 2) > 0.9) handle << i << (i % 10 == 0 ? "\n" : " ");
      if (mesh.V(i, 2) < 0.1) fixed << i << "\n";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  [[nodiscard]] std::string path(const std::string& leaf) const { return (dir_ / leaf).string(); }
  void write(const std::string& leaf, const std::string& text) const { std::ofstream(dir_ / leaf) << text; }

  fs::path dir_;
};

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_F(DeformCli, HandleAndFixedFilesGiveAMeshAndCompleteMetrics) {
  const RunResult run =
      run_pushpull("deform " + kHemisphere.string() + " --handle " + path("handle.txt") + " --fixed " +
                   path("fixed.txt") + " --displacement 0 0 0.3 --method asan --out " + path("out.off") +
                   " --metrics " + path("metrics.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find(path("out.off")), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(path("metrics.json")), std::string::npos) << run.output;

  const pd::Mesh in = pd::read_mesh(kHemisphere);
  const pd::Mesh out = pd::read_mesh(path("out.off"));
  ASSERT_EQ(out.V.rows(), in.V.rows());
  EXPECT_EQ(out.F, in.F);
  EXPECT_NEAR((out.V - in.V).rowwise().norm().maxCoeff(), 0.3, 1e-9);  // the handle moved by |d|

  const nlohmann::json m = read_json(path("metrics.json"));
  for (const char* key :
       {"method", "mu", "vertices", "roi_vertices", "iterations", "converged", "energy_trace", "timing_ms",
        "max_displacement", "gaussian_sign_flip_fraction", "along_d_norm", "orthogonal_norm", "warnings",
        "input", "d", "handle_count", "fixed_count", "sections"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  for (const char* key : {"precompute", "factorize", "solve", "per_iteration"}) {
    EXPECT_TRUE(m["timing_ms"].contains(key)) << key;
  }
  EXPECT_EQ(m["method"], "asan");
  EXPECT_EQ(m["vertices"], in.V.rows());
  EXPECT_EQ(m["energy_trace"].size(), m["iterations"].get<std::size_t>());
  EXPECT_NEAR(m["max_displacement"].get<double>(), 0.3, 1e-9);
  EXPECT_GT(m["along_d_norm"].get<double>(), 0.0);
  // asan keeps the sphere elliptic at this pull.
  EXPECT_EQ(m["gaussian_sign_flip_fraction"].get<double>(), 0.0);
  // The reversals again under raised bands (metrics.hpp): three, none reversed, radii L / sqrt(band).
  const auto& bands = m["curvature"]["reversals_by_band"];
  ASSERT_EQ(bands.size(), 3u);
  const double L = m["curvature"]["reference_length"].get<double>();
  for (const auto& band : bands) {
    EXPECT_EQ(band["reversals"].get<std::size_t>(), 0u);
    EXPECT_NEAR(band["radius_below"].get<double>(), L / std::sqrt(band["band"].get<double>()), 1e-12);
  }
  EXPECT_GT(bands[0]["compared"].get<std::size_t>(), 0u);  // the hemisphere (radius ~ L / 2.5) is signed
  EXPECT_NE(run.output.find("reversals where clearly curved: 0 of "), std::string::npos) << run.output;
  // Planes perpendicular to d = +z cut the hemisphere in closed rings, before and after.
  ASSERT_EQ(m["sections"].size(), 5u);
  for (const auto& section : m["sections"]) {
    ASSERT_EQ(section["before"].size(), 1u);
    EXPECT_TRUE(section["before"][0]["closed"].get<bool>());
    EXPECT_GT(section["before"][0]["points"].size(), 10u);
    EXPECT_GE(section["after"].size(), 1u);
  }
}

TEST_F(DeformCli, HandleAtAndRoiRadiusWithExactIterationCountWritesPly) {
  const RunResult run =
      run_pushpull("deform " + kHemisphere.string() +
                   " --handle-at 0 0 1 --handle-radius 0.2 --roi-radius 0.8 --displacement 0 0 0.5"
                   " --method arap-sr --tolerance 0 --iterations 7 --out " +
                   path("out.ply") + " --metrics " + path("m.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(pd::read_mesh(path("out.ply")).V.rows(), 1861);
  const nlohmann::json m = read_json(path("m.json"));
  EXPECT_EQ(m["iterations"], 7);
  EXPECT_EQ(m["method"], "arap-sr");
  EXPECT_LT(m["roi_vertices"].get<int>(), 1861);
  EXPECT_GT(m["fixed_count"].get<int>(), 0);
}

TEST_F(DeformCli, ObjOutputAndOtherMethodsRun) {
  for (const char* method : {"arap-m", "sr-arap", "arap-n", "arap-h", "arap-sr-h", "arap-s"}) {
    const RunResult run =
        run_pushpull("deform " + kHemisphere.string() + " --handle " + path("handle.txt") + " --fixed " +
                     path("fixed.txt") + " --displacement 0.1 0 0.1 --iterations 5 --method " + method +
                     " --out " + path("out.obj") + " --metrics " + path("m.json"));
    ASSERT_EQ(run.status, 0) << method << "\n" << run.output;
    EXPECT_EQ(read_json(path("m.json"))["method"], method);
    EXPECT_EQ(pd::read_mesh(path("out.obj")).F.rows(), 3600);
  }
}

TEST_F(DeformCli, BadInputsExitNonZeroNamingTheFileAndProblem) {
  write("bad_token.txt", "1 2\n3 x7 4\n");
  write("nul_token.txt", std::string("1\n2x\0\x01y\n", 8));  // a damaged file's control bytes
  write("out_of_range.txt", "5\n99999\n");
  write("empty.txt", "# nothing\n");
  const std::string tail = " --out " + path("o.off") + " --metrics " + path("m.json");
  const std::string files = " --handle " + path("handle.txt") + " --fixed " + path("fixed.txt");
  struct Case {
    std::string arguments;
    std::string expected;  // must appear in the message
  };
  const Case cases[] = {
      {"deform " + path("missing.off") + files + " --displacement 0 0 1" + tail, path("missing.off")},
      {"deform " + kHemisphere.string() + " --handle " + path("bad_token.txt") + " --fixed " +
           path("fixed.txt") + " --displacement 0 0 1" + tail,
       path("bad_token.txt") + ":2: 'x7' is not a vertex index"},
      {"deform " + kHemisphere.string() + " --handle " + path("nul_token.txt") + " --fixed " +
           path("fixed.txt") + " --displacement 0 0 1" + tail,
       path("nul_token.txt") + ":2: '2x??y' is not a vertex index"},  // not sent to the terminal raw
      {"deform " + kHemisphere.string() + " --handle " + path("out_of_range.txt") + " --fixed " +
           path("fixed.txt") + " --displacement 0 0 1" + tail,
       path("out_of_range.txt") + ":2: vertex index 99999 out of range"},
      {"deform " + kHemisphere.string() + " --handle " + path("empty.txt") + " --fixed " + path("fixed.txt") +
           " --displacement 0 0 1" + tail,
       path("empty.txt") + ": no vertex indices"},
      {"deform " + kHemisphere.string() + " --handle " + path("nope.txt") + " --fixed " + path("fixed.txt") +
           " --displacement 0 0 1" + tail,
       path("nope.txt") + ": cannot open"},
      {"deform " + kHemisphere.string() + files + " --displacement 0 0 1 --method arap-x" + tail, "arap-x"},
      {"deform " + kHemisphere.string() + files + " --displacement 0 0 0" + tail, "zero displacement"},
      {"deform " + kHemisphere.string() + files + " --displacement 0 0 1 --out " + path("o.stl") +
           " --metrics " + path("m.json"),
       path("o.stl") + ": unsupported output format"},
      {"deform " + kHemisphere.string() + " --handle " + path("handle.txt") + " --displacement 0 0 1" + tail,
       "--roi-radius"},
      {"deform " + kHemisphere.string() +
           " --handle-at 5 5 5 --handle-radius 0.1 --roi-radius 1 --displacement 0 0 1" + tail,
       "farther than --handle-radius"},
  };
  for (const Case& c : cases) {
    const RunResult run = run_pushpull(c.arguments);
    EXPECT_NE(run.status, 0) << c.arguments;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in:\n"
                                                              << run.output;
  }
  EXPECT_FALSE(fs::exists(path("o.off")));  // nothing half-done was written
  EXPECT_FALSE(fs::exists(path("m.json")));
}

// Tessellated CAD: two patches written separately, the seam's vertices once per patch (as `pushpull info`
// counts them). deform welds them as the headset review does: a pull on one patch bends the other along with
// it instead of tearing the seam open by |d|; the file comes back with its own vertices, each seam copy
// moved alike. Index files name the file's own vertices.
TEST_F(DeformCli, PatchesWithSeamVerticesTwiceDeformAsOneSurface) {
  // Patch A: x in [0, 1]; patch B: x in [1, 2]; 11 x 11 vertices each, y in [0, 1]; the column x = 1 twice.
  write("patches.off", two_patches_off(0.0));
  // The handle: patch A's vertex (0.9, 0.5); fixed: the outer ends x = 0 (patch A) and x = 2 (patch B).
  write("patch_handle.txt", std::to_string(5 * 11 + 9) + "\n");
  std::string fixed;
  for (int j = 0; j <= 10; ++j)
    fixed += std::to_string(j * 11) + " " + std::to_string(121 + j * 11 + 10) + "\n";
  write("patch_fixed.txt", fixed);
  const RunResult run =
      run_pushpull("deform " + path("patches.off") + " --handle " + path("patch_handle.txt") + " --fixed " +
                   path("patch_fixed.txt") + " --roi-radius 5" + " --displacement 0 0 0.05 --out " +
                   path("o.off") + " --metrics " + path("m.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("welded: 242 vertices of the file's triangles -> 231 (2 pieces -> 1 component)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("index files and the output keep the file's numbering"), std::string::npos)
      << run.output;
  const pd::Mesh out = pd::read_mesh(path("o.off"));
  ASSERT_EQ(out.V.rows(), 242);
  for (int j = 0; j <= 10; ++j) {
    const int a = j * 11 + 10, b = 121 + j * 11;  // the seam's two copies
    EXPECT_EQ(out.V.row(a), out.V.row(b)) << "seam row " << j;
  }
  EXPECT_NEAR(out.V(5 * 11 + 9, 2), 0.05, 1e-12);  // the handle moved by d
  EXPECT_GT(out.V(121 + 5 * 11 + 1, 2), 0.01);     // patch B, beside the seam, bent along
  EXPECT_EQ(read_json(path("m.json")).at("vertices").get<int>(), 231);

  // Written in another format: the file's own 242 vertices and 400 triangles in its numbering (the index
  // files' numbers name the same points), not the welded surface's 231.
  const RunResult as_obj =
      run_pushpull("deform " + path("patches.off") + " --handle " + path("patch_handle.txt") + " --fixed " +
                   path("patch_fixed.txt") + " --roi-radius 5" + " --displacement 0 0 0.05 --out " +
                   path("o.obj") + " --metrics " + path("m2.json"));
  ASSERT_EQ(as_obj.status, 0) << as_obj.output;
  const pd::Mesh obj = pd::read_mesh(path("o.obj"));
  ASSERT_EQ(obj.V.rows(), 242);
  EXPECT_EQ(obj.F.rows(), 400);
  EXPECT_EQ(obj.V, out.V);

  // Held on one patch's copy of a seam vertex, pulled on the other's: named as the files number them.
  write("seam_handle.txt", std::to_string(5 * 11 + 10) + "\n");
  write("seam_fixed.txt", std::to_string(121 + 5 * 11) + "\n");
  auto held_and_fixed = [&](const std::string& handle, const std::string& fixed) {
    return run_pushpull("deform " + path("patches.off") + " " + handle + " --fixed " + path(fixed) +
                        " --displacement 0 0 0.05 --out " + path("o2.off") + " --metrics " + path("m3.json"));
  };
  const RunResult both = held_and_fixed("--handle " + path("seam_handle.txt"), "seam_fixed.txt");
  EXPECT_EQ(both.status, 1) << both.output;
  EXPECT_NE(both.output.find("file vertex 65 of " + path("seam_handle.txt") + " and vertex 176 of " +
                             path("seam_fixed.txt") + " are one point once the seams are welded"),
            std::string::npos)
      << both.output;
  // The same vertex in both files, and a fixed vertex inside a handle picked around a point.
  write("seam_fixed2.txt", "176 65\n");
  const RunResult listed_twice = held_and_fixed("--handle " + path("seam_handle.txt"), "seam_fixed2.txt");
  EXPECT_EQ(listed_twice.status, 1) << listed_twice.output;
  EXPECT_NE(listed_twice.output.find("file vertex 65 is in both " + path("seam_handle.txt") + " and " +
                                     path("seam_fixed2.txt")),
            std::string::npos)
      << listed_twice.output;
  const RunResult picked = held_and_fixed("--handle-at 1 0.5 0 --handle-radius 0.01", "seam_fixed.txt");
  EXPECT_EQ(picked.status, 1) << picked.output;
  EXPECT_NE(picked.output.find("file vertex 176 of " + path("seam_fixed.txt") +
                               " lies in the handle picked around --handle-at"),
            std::string::npos)
      << picked.output;
  EXPECT_FALSE(fs::exists(path("o2.off")));
}

// Patches whose seam copies lie a little apart (4.5e-5 of the diagonal here: tessellated CAD written with
// less precision) stay torn at the default weld; --weld-tolerance, as `info` takes it, welds them for the
// solve too, and the metrics say which weld the model was loaded with.
TEST_F(DeformCli, AWiderWeldToleranceJoinsPatchesAFileLeftApart) {
  write("gap.off", two_patches_off(1e-4));
  write("gap_handle.txt", std::to_string(5 * 11 + 9) + "\n");
  std::string fixed;
  for (int j = 0; j <= 10; ++j)
    fixed += std::to_string(j * 11) + " " + std::to_string(121 + j * 11 + 10) + "\n";
  write("gap_fixed.txt", fixed);
  auto pull = [&](const std::string& weld) {
    return run_pushpull("deform " + path("gap.off") + " --handle " + path("gap_handle.txt") + " --fixed " +
                        path("gap_fixed.txt") + " --roi-radius 5 --displacement 0 0 0.05 --out " +
                        path("g.off") + " --metrics " + path("g.json") + weld);
  };
  const RunResult apart = pull("");
  ASSERT_EQ(apart.status, 0) << apart.output;
  EXPECT_EQ(read_json(path("g.json")).at("vertices").get<int>(), 242) << apart.output;  // not welded
  EXPECT_DOUBLE_EQ(read_json(path("g.json")).at("weld_tolerance").get<double>(), 1e-5);
  const RunResult joined = pull(" --weld-tolerance 1e-4");
  ASSERT_EQ(joined.status, 0) << joined.output;
  EXPECT_NE(joined.output.find("(2 pieces -> 1 component)"), std::string::npos) << joined.output;
  EXPECT_EQ(read_json(path("g.json")).at("vertices").get<int>(), 231);  // the seam's 11 copies welded
  const pd::Mesh welded = pd::read_mesh(path("g.off"));
  for (int j = 0; j <= 10; ++j)  // the seam's copies moved alike: one surface
    EXPECT_NEAR((welded.V.row(j * 11 + 10) - welded.V.row(121 + j * 11)).norm(), 1e-4, 1e-9) << j;
  EXPECT_DOUBLE_EQ(read_json(path("g.json")).at("weld_tolerance").get<double>(), 1e-4);
  const RunResult refused = pull(" --weld-tolerance -1");
  EXPECT_EQ(refused.status, 2) << refused.output;
}

TEST_F(DeformCli, AModelWithoutTrianglesIsRefusedNamingTheFile) {
  write("zero.off", "OFF\n0 0 0\n");
  write("nothing.obj", "# no vertices\n");
  for (const std::string& file : {path("zero.off"), path("nothing.obj")}) {
    const RunResult run = run_pushpull("deform " + file +
                                       " --handle-at 0 0 0 --handle-radius 0.1 --roi-radius 1 --displacement "
                                       "0 0 0.05 --out " +
                                       path("o.off") + " --metrics " + path("m.json"));
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find(file + ": the model has no triangles"), std::string::npos) << run.output;
  }
}
