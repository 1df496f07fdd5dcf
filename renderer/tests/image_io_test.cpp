#include "pushpull/renderer/image_io.hpp"
#include "pushpull/renderer/colormap.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "test_scenes.hpp"

namespace pushpull::renderer {
namespace {

TEST(ImageIo, PngRoundTripAndDiffOfIdenticalImagesIsZero) {
  TextureRGBA8 image{3, 2, std::vector<uint8_t>(24, 0)};
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 10);
  const auto path = testing::output_dir() / "roundtrip.png";
  write_png(path, image);
  const TextureRGBA8 back = read_png(path);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(compare_images(image, back, 0).differing_pixels, 0u);
}

TEST(ImageIo, DiffFlagsChangedPixels) {
  TextureRGBA8 a{4, 4, std::vector<uint8_t>(64, 100)};
  TextureRGBA8 b = a;
  b.pixels[4 * 5] = 140;
  const ImageComparison cmp = compare_images(a, b, 8);
  EXPECT_EQ(cmp.differing_pixels, 1u);
  EXPECT_EQ(cmp.max_difference, 40u);
  EXPECT_EQ(cmp.diff.pixels[4 * 5 + 1], 0);  // flagged magenta
  EXPECT_FALSE(compare_images(a, TextureRGBA8{2, 2, std::vector<uint8_t>(16, 0)}, 8).same_size);
}

TEST(ImageIo, ReadingAMissingFileNamesIt) {
  try {
    (void)read_png("/nonexistent/x.png");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.png"), std::string::npos);
  }
}

TEST(Colormap, EndpointsAndMonotoneHueOrder) {
  EXPECT_NEAR(displacement_colour(0.0f).b, 0.45f, 1e-6f);
  EXPECT_NEAR(displacement_colour(1.0f).r, 0.85f, 1e-6f);
  EXPECT_EQ(displacement_colour(-1.0f), displacement_colour(0.0f));
  EXPECT_EQ(displacement_colour(2.0f), displacement_colour(1.0f));
  EXPECT_GT(curvature_sign_colour(1.0f, 0.1f).r, 0.9f);   // yellow
  EXPECT_GT(curvature_sign_colour(-1.0f, 0.1f).b, 0.9f);  // blue
  EXPECT_EQ(curvature_sign_colour(0.05f, 0.1f), glm::vec3(0.55f));
}

TEST(Geometry, NormalsOfAFlatSheetPointUp) {
  const RenderMesh sheet = testing::make_sheet(4);
  const auto n = compute_vertex_normals(sheet.positions, sheet.indices);
  for (size_t v = 0; v < n.size(); v += 3) EXPECT_NEAR(n[v + 2], 1.0f, 1e-6f);
}

TEST(Geometry, ArrowSpansP0ToP1) {
  const RenderMesh arrow = make_arrow({0, 0, 0}, {0, 0, 2}, 0.05f, 0);
  const Bounds b = compute_bounds(arrow.positions);
  EXPECT_NEAR(b.min.z, 0.0f, 1e-6f);
  EXPECT_NEAR(b.max.z, 2.0f, 1e-6f);
  EXPECT_NEAR(b.max.x, 0.1f, 1e-5f);  // head is twice the shaft radius
}

TEST(Camera, FrameBoundsKeepsTheBoundingSphereInView) {
  const Bounds b{{-2, -1, -3}, {4, 1, 3}};
  const View v = frame_bounds(b, OrbitCamera{}, 16.0f / 9.0f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                           (i & 4) ? b.max.z : b.min.z);
    const glm::vec4 clip = v.projection * v.view * glm::vec4(corner, 1.0f);
    EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
    EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
    EXPECT_GE(clip.z / clip.w, 0.0f);
    EXPECT_LE(clip.z / clip.w, 1.0f);
  }
}

}  // namespace
}  // namespace pushpull::renderer
