// `pushpull render` end to end: PNGs from OFF and glTF models on lavapipe with validation, the
// displacement colour map where the displacement is known, and readable errors.
#include <gtest/gtest.h>

#include "command_runner.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using Result = pushpull::testing::CommandResult;
const auto& run = pushpull::testing::run_pushpull;

fs::path temp_dir() {
  const fs::path dir = fs::path(PUSHPULL_BINARY_DIR) / "render-cli-test";
  fs::create_directories(dir);
  return dir;
}

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;
  [[nodiscard]] std::array<int, 3> at(int x, int y) const {
    const size_t i = (size_t(y) * size_t(width) + size_t(x)) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
  }
};

Png load_png(const fs::path& path) {
  Png png;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 4);
  if (data != nullptr) {
    png.rgba.assign(data, data + size_t(png.width) * size_t(png.height) * 4);
    stbi_image_free(data);
  }
  return png;
}

// An n x n sheet over [-1, 1]^2 at z = 0, and the same sheet with z = 0.05 (x + 1): displacement
// magnitude 0 at x = -1 growing linearly to 0.1 at x = 1.
void write_sheets(const fs::path& flat, const fs::path& lifted, int n) {
  std::ofstream a(flat), b(lifted);
  const int vertices = (n + 1) * (n + 1), faces = 2 * n * n;
  a << "OFF\n" << vertices << " " << faces << " 0\n";
  b << "OFF\n" << vertices << " " << faces << " 0\n";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1.0 + 2.0 * j / n, y = -1.0 + 2.0 * i / n;
      a << x << " " << y << " 0\n";
      b << x << " " << y << " " << 0.05 * (x + 1.0) << "\n";
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * (n + 1) + j, w = v + n + 1;
      a << "3 " << v << " " << v + 1 << " " << w + 1 << "\n3 " << v << " " << w + 1 << " " << w << "\n";
      b << "3 " << v << " " << v + 1 << " " << w + 1 << "\n3 " << v << " " << w + 1 << " " << w << "\n";
    }
}

TEST(RenderCli, WritesAPngOfAnOffModelWithValidationClean) {
  const fs::path out = temp_dir() / "hemisphere.png";
  fs::remove(out);
  const Result r = run("render " + std::string(PUSHPULL_SHARED_DATA) + "/meshes/hemisphere.off --out " +
                       out.string() + " --size 160 120 --up 0 0 1 --validation");
  ASSERT_EQ(r.status, 0) << r.output;
  const Png png = load_png(out);
  EXPECT_EQ(png.width, 160);
  EXPECT_EQ(png.height, 120);
  // Default camera frames the model: the centre is the model, a corner the background.
  EXPECT_NE(png.at(80, 60), png.at(1, 1));
  EXPECT_EQ(r.output.find("names no up axis"), std::string::npos) << r.output;  // --up given
  // The bonnet, modelled Z-up, without --up: drawn on its side, and said (as info and review say it).
  const Result hood = run("render " + std::string(PUSHPULL_SOURCE_DIR) + "/examples/hood.off --out " +
                          (temp_dir() / "hood.png").string() + " --size 64 48");
  ASSERT_EQ(hood.status, 0) << hood.output;
  EXPECT_NE(hood.output.find("pushpull render: note: "), std::string::npos) << hood.output;
  EXPECT_NE(hood.output.find("give --up 0 0 1"), std::string::npos) << hood.output;
}

// The same lit sheet at extreme scales and far from the origin: a sheet 2e-9 across (it came out blank: the
// camera kept at least 1e-6 from it), one 2e12 across (black: its normals' squared norms overflowed the
// floats) and one 1e9 from the origin (beyond what 32-bit floats resolve for its size: refused as a picture
// of nothing, until the model was drawn relative to its centre) look like the sheet 2 across.
TEST(RenderCli, ExtremeScalesAndAModelFarFromTheOriginDrawLikeTheSheetAtTheOrigin) {
  const fs::path flat = temp_dir() / "scale_sheet.off", lifted = temp_dir() / "scale_sheet_lifted.off";
  write_sheets(flat, lifted, 8);
  auto scaled = [&](double scale, double offset, const std::string& name) {
    std::ifstream in(lifted);
    std::string header, counts;
    std::getline(in, header);
    std::getline(in, counts);
    std::ofstream out(temp_dir() / name);
    out.precision(17);
    out << header << "\n" << counts << "\n";
    for (int v = 0; v < 81; ++v) {
      double x = 0, y = 0, z = 0;
      in >> x >> y >> z;
      out << x * scale + offset << " " << y * scale << " " << z * scale << "\n";
    }
    out << in.rdbuf();
    return (temp_dir() / name).string();
  };
  const std::string common = " --size 64 64 --up 0 0 1 --camera 20 40";
  const fs::path reference = temp_dir() / "scale_1.png";
  ASSERT_EQ(run("render " + scaled(1.0, 0.0, "s1.off") + " --out " + reference.string() + common).status, 0);
  const Png expected = load_png(reference);
  for (const auto& [scale, offset] : {std::pair{1e-9, 0.0}, std::pair{1e12, 0.0}, std::pair{1.0, 1e9}}) {
    const fs::path out = temp_dir() / "scale_x.png";
    const Result r = run("render " + scaled(scale, offset, "sx.off") + " --out " + out.string() + common);
    ASSERT_EQ(r.status, 0) << scale << ": " << r.output;
    const Png png = load_png(out);
    ASSERT_EQ(png.width, 64);
    int differing = 0;  // every pixel: the sheet, its shading and the background
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c)
          if (std::abs(png.at(x, y)[c] - expected.at(x, y)[c]) > 12) {
            ++differing;
            break;
          }
    EXPECT_LE(differing, 8) << "scale " << scale << ", offset " << offset;
  }
}

TEST(RenderCli, DisplacementColourMapFollowsAKnownDisplacement) {
  const fs::path flat = temp_dir() / "sheet.off", lifted = temp_dir() / "sheet_lifted.off";
  write_sheets(flat, lifted, 32);
  const fs::path out = temp_dir() / "sheet_displacement.png";
  const Result r =
      run("render " + flat.string() + " --deformed " + lifted.string() + " --out " + out.string() +
          " --size 200 200 --color displacement --flat --no-legend --eye 0 0 4 --target 0 0 0"
          " --validation");
  ASSERT_EQ(r.status, 0) << r.output;
  const Png png = load_png(out);
  ASSERT_EQ(png.width, 200);
  // Left end (|d| ~ 0): dark blue; middle (|d| ~ max/2): cyan-green; right end (|d| ~ max): red.
  const auto left = png.at(8, 100), middle = png.at(100, 100), right = png.at(192, 100);
  EXPECT_GT(left[2], left[0] + 60) << "left should be blue";
  EXPECT_LT(left[1], 120) << "left should be dark blue";
  EXPECT_GT(middle[1], middle[0] + 60) << "middle should be green/cyan";
  EXPECT_GT(right[0], right[1] + 40) << "right should be red/orange";
  EXPECT_GT(right[0], right[2] + 100) << "right should be red/orange";
}

TEST(RenderCli, GltfWithMaterialsCurvatureAndStereo) {
  const std::string car =
      std::string(PUSHPULL_SHARED_DATA) + "/gltf/CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb";
  const fs::path out = temp_dir() / "truck.png";
  Result r = run("render " + car + " --out " + out.string() + " --size 160 100 --validation");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(load_png(out).width, 160);
  const fs::path curvature = temp_dir() / "truck_curvature.png";
  r = run("render " + car + " --out " + curvature.string() +
          " --size 160 100 --color curvature-sign --validation");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path stereo = temp_dir() / "truck_stereo.png";
  r = run("render " + car + " --out " + stereo.string() + " --size 100 100 --stereo 0.06 --validation");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(load_png(stereo).width, 200);  // left | right
}

// The p0 -> p1 arrow is drawn on top of the surface: an arrow inside the dome, behind its wall as seen
// from the camera, still shows in the picture (and the same picture without it has no arrow colour).
TEST(RenderCli, ArrowInsideTheSurfaceStaysVisible) {
  const std::string dome = std::string(PUSHPULL_SHARED_DATA) + "/meshes/hemisphere.off";
  auto arrow_pixels = [](const Png& png) {
    int n = 0;
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x) {
        const auto c = png.at(x, y);
        n += (c[0] > 200 && c[1] < 90 && c[2] > 170) ? 1 : 0;  // the magenta of kArrowColour
      }
    return n;
  };
  const fs::path with = temp_dir() / "arrow_inside.png", without = temp_dir() / "no_arrow.png";
  Result r =
      run("render " + dome + " --up 0 0 1 --arrow 0 0 0.9 0 0 0.2 --size 320 240 --out " + with.string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("render " + dome + " --up 0 0 1 --size 320 240 --out " + without.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(arrow_pixels(load_png(without)), 0);
  EXPECT_GT(arrow_pixels(load_png(with)), 20);
}

TEST(RenderCli, ErrorsNameTheFileAndTheProblem) {
  Result r = run("render /nonexistent/model.off --out /tmp/x.png");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/nonexistent/model.off"), std::string::npos) << r.output;
  const fs::path flat = temp_dir() / "sheet_a.off", lifted = temp_dir() / "sheet_b.off";
  write_sheets(flat, lifted, 4);
  r = run("render " + flat.string() + " --deformed " + std::string(PUSHPULL_SHARED_DATA) +
          "/meshes/hemisphere.off --out /tmp/x.png");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("hemisphere.off"), std::string::npos) << r.output;
  r = run("render " + flat.string() + " --out /nonexistent-dir/x.png --size 16 16");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/nonexistent-dir/x.png"), std::string::npos) << r.output;
  // A name that promises another format is refused, not written as a PNG under it.
  const fs::path jpeg = temp_dir() / "picture.jpg";
  r = run("render " + flat.string() + " --out " + jpeg.string() + " --size 16 16");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(jpeg.string() + ": render writes PNG pictures; give --out a name ending in .png"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(jpeg));
  // Where the curvature sign reversed needs a deformed shape to compare with.
  r = run("render " + flat.string() + " --out " + (temp_dir() / "reversal.png").string() +
          " --color curvature-reversal --size 16 16");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--color curvature-reversal needs --deformed"), std::string::npos) << r.output;
}

// A sample count the device cannot render (lavapipe: 1 and 4) wrote a picture of noise and exit status 0; it
// is refused with the counts the device has (a GPU that has it draws the sheet). A picture that would show
// nothing says its likely cause (too small), and a model with no triangle of non-zero area is refused as it
// loads (it was drawn as nothing, blamed on its scale).
TEST(RenderCli, WhatCannotBeDrawnIsRefusedWithItsCause) {
  const fs::path flat = temp_dir() / "sheet_c.off", lifted = temp_dir() / "sheet_d.off";
  write_sheets(flat, lifted, 4);
  for (const char* samples : {"2", "8"}) {
    const fs::path out = temp_dir() / (std::string("samples") + samples + ".png");
    fs::remove(out);
    const Result r = run("render " + flat.string() + " --out " + out.string() +
                         " --size 64 48 --up 0 0 1 --samples " + samples);
    if (r.status == 0) {  // the device renders that count: the sheet is drawn
      const Png png = load_png(out);
      EXPECT_NE(png.at(32, 24), png.at(1, 1)) << samples;
      continue;
    }
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(std::string("MSAA with ") + samples + " samples: "), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(" renders 1"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << samples;
  }
  Result r = run("render " + flat.string() + " --out " + (temp_dir() / "tiny.png").string() +
                 " --size 2 2 --up 0 0 1 --no-legend");
  if (r.status != 0) {
    EXPECT_NE(r.output.find("--size 2 2 is too small"), std::string::npos) << r.output;
  }
  const fs::path line = temp_dir() / "line.off";
  std::ofstream(line) << "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n";
  r = run("render " + line.string() + " --out " + (temp_dir() / "line.png").string() + " --size 64 48");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("line.off: every triangle (1) has zero area in the file itself"), std::string::npos)
      << r.output;
}

}  // namespace
