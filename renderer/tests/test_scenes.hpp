// Procedural geometry and helpers shared by the renderer tests (no external assets).
#pragma once

#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/image_io.hpp"
#include "pushpull/renderer/offscreen_target.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/renderer/types.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace pushpull::renderer::testing {

// UV sphere of radius r centred at the origin; scalars = z (so the colour maps vary over it).
inline RenderMesh make_sphere(float r, int stacks, int slices) {
  RenderMesh m;
  for (int i = 0; i <= stacks; ++i) {
    const float theta = glm::pi<float>() * float(i) / float(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float phi = glm::two_pi<float>() * float(j) / float(slices);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.insert(m.positions.end(), {r * n.x, r * n.y, r * n.z});
      m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
      m.uvs.insert(m.uvs.end(), {float(j) / float(slices), float(i) / float(stacks)});
      m.scalars.push_back(n.z);
    }
  }
  const uint32_t row = uint32_t(slices + 1);
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + row;
      // Counter-clockwise seen from outside.
      m.indices.insert(m.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  return m;
}

// Flat sheet in the z = 0 plane over [-1, 1]^2, n x n quads, facing +Z; scalars = (x + 1) / 2.
inline RenderMesh make_sheet(int n) {
  RenderMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float x = -1.0f + 2.0f * float(j) / float(n), y = -1.0f + 2.0f * float(i) / float(n);
      m.positions.insert(m.positions.end(), {x, y, 0.0f});
      m.normals.insert(m.normals.end(), {0.0f, 0.0f, 1.0f});
      m.scalars.push_back(0.5f * (x + 1.0f));
    }
  const uint32_t row = uint32_t(n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + row;
      m.indices.insert(m.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
    }
  return m;
}

// Camera straight down -Z at the sheet, the [-1, 1]^2 square filling the view (45 deg, distance fitted).
inline View sheet_camera() {
  View v;
  const float fov = glm::radians(45.0f);
  const float d = 1.0f / std::tan(0.5f * fov);
  v.view = glm::lookAt(glm::vec3(0.0f, 0.0f, d), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  v.projection = perspective(fov, 1.0f, 0.1f * d, 10.0f * d);
  return v;
}

inline glm::u8vec4 pixel(const TextureRGBA8& image, uint32_t x, uint32_t y) {
  const size_t i = (size_t(y) * image.width + x) * 4;
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2], image.pixels[i + 3]};
}

inline std::filesystem::path reference_dir() {
  return std::filesystem::path(PUSHPULL_SOURCE_DIR) / "renderer" / "tests" / "reference";
}
inline std::filesystem::path output_dir() {
  const auto dir = std::filesystem::path(PUSHPULL_BINARY_DIR) / "renderer" / "test-output";
  std::filesystem::create_directories(dir);
  return dir;
}

// Compares `image` with reference/<name>.png (per-channel tolerance; at most max_bad_pixels over it).
// PUSHPULL_UPDATE_REFERENCES=1 rewrites the reference instead. On failure writes <name>.actual.png and
// <name>.diff.png into the build tree.
inline void expect_matches_reference(const TextureRGBA8& image, const std::string& name,
                                     uint32_t tolerance = 8, uint32_t max_bad_pixels = 0) {
  const auto reference = reference_dir() / (name + ".png");
  const char* update = std::getenv("PUSHPULL_UPDATE_REFERENCES");
  if (update != nullptr && std::string(update) == "1") {
    write_png(reference, image);
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(reference))
      << "missing reference image " << reference << " (run with PUSHPULL_UPDATE_REFERENCES=1 and inspect it)";
  const TextureRGBA8 expected = read_png(reference);
  const ImageComparison cmp = compare_images(image, expected, tolerance);
  const bool ok = cmp.same_size && cmp.differing_pixels <= max_bad_pixels;
  if (!ok) {
    write_png(output_dir() / (name + ".actual.png"), image);
    if (cmp.same_size) write_png(output_dir() / (name + ".diff.png"), cmp.diff);
  }
  EXPECT_TRUE(ok) << name << ": " << cmp.differing_pixels << " pixels differ by more than " << tolerance
                  << " (max " << cmp.max_difference << ", mean " << cmp.mean_difference << "); see "
                  << (output_dir() / (name + ".diff.png"));
}

}  // namespace pushpull::renderer::testing
