// `pushpull render --color curvature-sign` draws deform's sign rule: a coarse cube (6 flat panels whose
// only vertices are its corners, each with angle defect pi/2) is drawn flat grey instead of taking its
// corners' yellow; a smooth dome is drawn yellow.
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
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::path(PUSHPULL_BINARY_DIR) / "render-curvature-test";
  fs::create_directories(dir);
  return dir;
}

// RGB at the centre of a PNG.
std::array<int, 3> centre_pixel(const fs::path& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (data == nullptr) return {-1, -1, -1};
  const std::size_t i = (std::size_t(h / 2) * std::size_t(w) + std::size_t(w / 2)) * 3;
  const std::array<int, 3> rgb = {data[i], data[i + 1], data[i + 2]};
  stbi_image_free(data);
  return rgb;
}

std::array<int, 3> render_curvature(const fs::path& model, const std::string& name) {
  const fs::path out = temp_dir() / (name + ".png");
  const auto r = pushpull::testing::run_pushpull("render " + model.string() + " --out " + out.string() +
                                                 " --size 64 64 --color curvature-sign --flat --no-legend");
  EXPECT_EQ(r.status, 0) << r.output;
  return centre_pixel(out);
}

TEST(RenderCurvature, CoarseFlatPanelsAreDrawnFlat) {
  const fs::path cube = temp_dir() / "cube.off";
  {
    std::ofstream off(cube);
    off << "OFF\n8 12 0\n";
    for (int i = 0; i < 8; ++i) off << (i & 1) << " " << ((i >> 1) & 1) << " " << ((i >> 2) & 1) << "\n";
    off << "3 0 2 1\n3 1 2 3\n3 4 5 6\n3 5 7 6\n3 0 1 4\n3 1 5 4\n"
           "3 2 6 3\n3 3 6 7\n3 0 4 2\n3 2 4 6\n3 1 3 5\n3 3 7 5\n";
  }
  const auto panel = render_curvature(cube, "cube");
  // Grey (K = 0): red, green and blue alike; the corners' yellow would have blue far below red.
  EXPECT_LT(std::abs(panel[0] - panel[2]), 20) << panel[0] << " " << panel[1] << " " << panel[2];
  EXPECT_LT(std::abs(panel[0] - panel[1]), 20) << panel[0] << " " << panel[1] << " " << panel[2];

  const auto dome = render_curvature(fs::path(PUSHPULL_SHARED_DATA) / "meshes" / "hemisphere.off", "dome");
  EXPECT_GT(dome[0], dome[2] + 80) << "a sphere is elliptic: yellow, got " << dome[0] << " " << dome[1] << " "
                                   << dome[2];
}

}  // namespace
