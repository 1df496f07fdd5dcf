// Offscreen rendering on lavapipe with validation: reference images, colour maps, overlays, stereo,
// handed-in devices, streaming.
#include "pushpull/renderer/colormap.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "test_scenes.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <thread>
#include <vector>

namespace pushpull::renderer {
namespace {

using testing::make_sheet;
using testing::make_sphere;
using testing::pixel;

constexpr uint32_t kSize = 256;

Context make_context() {
  ContextOptions options;
  options.validation = true;
  return Context::create(options);
}

// sRGB-encoded 8-bit value of a linear colour (what an SRGB target stores).
glm::ivec3 encoded(const glm::vec3& linear) {
  return {int(std::lround(255.0f * linear_to_srgb(linear.r))),
          int(std::lround(255.0f * linear_to_srgb(linear.g))),
          int(std::lround(255.0f * linear_to_srgb(linear.b)))};
}

void expect_colour_near(const glm::u8vec4& got, const glm::ivec3& want, int tolerance,
                        const std::string& where) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(int(got[c]), want[c], tolerance)
        << where << " channel " << c << ": got (" << int(got.r) << "," << int(got.g) << "," << int(got.b)
        << ") want (" << want.r << "," << want.g << "," << want.b << ")";
}

View sphere_view() {
  Bounds b{glm::vec3(-1.0f), glm::vec3(1.0f)};
  OrbitCamera camera;
  return frame_bounds(b, camera, 1.0f);
}

// `flat` (a make_sheet) with a Gaussian bump 0.4 high at the centre, its scalars the height / 0.4 (0..1 for
// the displacement map) and normals to match: a streamed shape's target.
RenderMesh bump_on(const RenderMesh& flat) {
  RenderMesh bent = flat;
  for (size_t v = 0; v < bent.vertex_count(); ++v) {
    const float x = bent.positions[3 * v], y = bent.positions[3 * v + 1];
    bent.positions[3 * v + 2] = 0.4f * std::exp(-4.0f * (x * x + y * y));
    bent.scalars[v] = bent.positions[3 * v + 2] / 0.4f;
  }
  bent.normals = compute_vertex_normals(bent.positions, bent.indices);
  return bent;
}

// The displacement map over [0, 1], unlit: the pixels are the map's colours.
FrameSettings unlit_displacement() {
  FrameSettings settings;
  settings.color_mode = ColorMode::displacement;
  settings.scalar_max = 1.0f;
  settings.lighting = false;
  return settings;
}

// `mesh` (a make_sheet) seen by the sheet camera, kSize x kSize, with `settings`.
TextureRGBA8 sheet_image(const Context& context, Renderer& renderer, MeshId mesh,
                         const FrameSettings& settings) {
  OffscreenTarget target(context, kSize, kSize);
  const View view = testing::sheet_camera();
  const Draw draw{mesh, glm::mat4(1.0f)};
  renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
  return target.read_back();
}

Material red_paint() {
  Material m;
  m.base_colour = {0.5f, 0.02f, 0.02f, 1.0f};
  m.metallic = 0.0f;
  m.roughness = 0.25f;
  m.clearcoat = 1.0f;
  return m;
}

TEST(Renderer, MaterialSphereMatchesReferenceWithoutValidationMessages) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh sphere = make_sphere(1.0f, 48, 96);
    sphere.submeshes.push_back({0, uint32_t(sphere.indices.size()), int(renderer.add_material(red_paint()))});
    const MeshId mesh = renderer.add_mesh(sphere);
    OffscreenTarget target(context, kSize, kSize);
    const View view = sphere_view();
    const Draw draw{mesh, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&draw, 1), FrameSettings{}, target.targets());
    const TextureRGBA8 image = target.read_back();
    testing::expect_matches_reference(image, "sphere_material", 8, 64);
    // Centre is the sphere, corners the background.
    const auto centre = pixel(image, kSize / 2, kSize / 2);
    EXPECT_GT(centre.r, centre.b + 20);
    expect_colour_near(pixel(image, 2, 2), encoded(glm::vec3(FrameSettings{}.clear_colour)), 2, "corner");
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// A sample count that is not one power of two, or one the device does not render colour and depth with,
// is refused naming the counts it has (lavapipe drew noise with 2 and 8); 1 always works.
TEST(Renderer, ASampleCountTheDeviceCannotRenderIsRefused) {
  Context context = make_context();
  const VkPhysicalDeviceLimits& limits = context.properties().limits;
  const VkSampleCountFlags supported =
      limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
  for (const VkSampleCountFlagBits samples :
       {VkSampleCountFlagBits(3), VkSampleCountFlagBits(0), VK_SAMPLE_COUNT_2_BIT, VK_SAMPLE_COUNT_64_BIT}) {
    RendererOptions options;
    options.samples = samples;
    if ((supported & VkSampleCountFlags(samples)) != 0 && (samples & (samples - 1)) == 0 && samples != 0) {
      EXPECT_NO_THROW(Renderer(context, options)) << samples;
      continue;
    }
    try {
      Renderer renderer(context, options);
      ADD_FAILURE() << samples << " samples accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(" renders 1"), std::string::npos) << e.what();
    }
  }
  RendererOptions one;
  one.samples = VK_SAMPLE_COUNT_1_BIT;
  EXPECT_NO_THROW(Renderer(context, one));
}

TEST(Renderer, DisplacementColourMapMatchesCpuMapOnSheet) {
  Context context = make_context();
  {
    Renderer renderer(context);
    const MeshId mesh = renderer.add_mesh(make_sheet(64));
    FrameSettings settings = unlit_displacement();
    const TextureRGBA8 image = sheet_image(context, renderer, mesh, settings);
    // scalar = (x + 1) / 2 across the sheet, which spans the image width.
    for (float t : {0.05f, 0.2f, 0.4f, 0.5f, 0.6f, 0.8f, 0.95f}) {
      const auto x = uint32_t(t * float(kSize));
      const float at_pixel = (float(x) + 0.5f) / float(kSize);
      expect_colour_near(pixel(image, x, kSize / 2), encoded(displacement_colour(at_pixel)), 6,
                         "t=" + std::to_string(t));
    }
    settings.lighting = true;
    testing::expect_matches_reference(sheet_image(context, renderer, mesh, settings), "sheet_displacement", 8,
                                      64);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

TEST(Renderer, CurvatureSignIsYellowPositiveBlueNegativeGreyZero) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh sheet = make_sheet(64);
    for (size_t v = 0; v < sheet.scalars.size(); ++v) {
      const float x = sheet.positions[3 * v];
      sheet.scalars[v] = x < -0.3f ? 2.5f : (x > 0.3f ? -2.5f : 0.0f);  // K > 0 | K = 0 | K < 0
    }
    const MeshId mesh = renderer.add_mesh(sheet);
    FrameSettings settings;
    settings.color_mode = ColorMode::curvature_sign;
    settings.curvature_epsilon = 1e-3f;
    settings.lighting = false;
    const TextureRGBA8 image = sheet_image(context, renderer, mesh, settings);
    expect_colour_near(pixel(image, kSize / 8, kSize / 2), encoded(curvature_sign_colour(1.0f, 0.0f)), 2,
                       "K>0");
    expect_colour_near(pixel(image, kSize / 2, kSize / 2), encoded(curvature_sign_colour(0.0f, 0.0f)), 2,
                       "K=0");
    expect_colour_near(pixel(image, 7 * kSize / 8, kSize / 2), encoded(curvature_sign_colour(-1.0f, 0.0f)), 2,
                       "K<0");
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

TEST(Renderer, OverlaysPaintHandleRedFixedBlueAndArrow) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh sheet = make_sheet(64);
    sheet.overlays.resize(sheet.vertex_count());
    for (size_t v = 0; v < sheet.overlays.size(); ++v) {
      const float x = sheet.positions[3 * v], y = sheet.positions[3 * v + 1];
      sheet.overlays[v].roi = std::abs(x) < 0.7f ? 1.0f : 0.0f;
      sheet.overlays[v].fixed = x < -0.7f ? 1.0f : 0.0f;
      sheet.overlays[v].handle = (std::abs(x) < 0.15f && std::abs(y) < 0.15f) ? 1.0f : 0.0f;
    }
    Material arrow_material;
    arrow_material.base_colour = glm::vec4(kArrowColour, 1.0f);
    arrow_material.unlit = true;
    const int arrow_id = int(renderer.add_material(arrow_material));
    const MeshId sheet_mesh = renderer.add_mesh(sheet);
    const MeshId arrow = renderer.add_mesh(
        make_arrow(glm::vec3(0.5f, -0.5f, 0.1f), glm::vec3(0.5f, 0.5f, 0.1f), 0.04f, arrow_id));
    OffscreenTarget target(context, kSize, kSize);
    const View view = testing::sheet_camera();
    const std::array<Draw, 2> draws{Draw{sheet_mesh, glm::mat4(1.0f)}, Draw{arrow, glm::mat4(1.0f)}};
    FrameSettings settings;
    settings.lighting = true;
    renderer.render(std::span(&view, 1), draws, settings, target.targets());
    const TextureRGBA8 image = target.read_back();
    testing::expect_matches_reference(image, "sheet_overlays", 8, 64);
    const auto handle = pixel(image, kSize / 2, kSize / 2);
    EXPECT_GT(handle.r, 2 * handle.g) << "handle should be red";
    const auto fixed = pixel(image, kSize / 16, kSize / 2);
    EXPECT_GT(fixed.b, 2 * fixed.r) << "fixed should be blue";
    const auto arrow_pixel = pixel(image, 3 * kSize / 4 + 2, kSize / 2);
    expect_colour_near(arrow_pixel, encoded(kArrowColour), 3, "arrow (unlit)");
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// The hover highlight (fixed and handle together) on the displacement map's top: magenta, apart from the
// map's red around it (a red highlight would vanish there).
TEST(Renderer, AHoverHighlightIsMagentaOnTheDisplacementMapsRed) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh sheet = make_sheet(64);
    sheet.scalars.assign(sheet.vertex_count(), 1.0f);  // everything at the map's top
    sheet.overlays.resize(sheet.vertex_count());
    for (size_t v = 0; v < sheet.overlays.size(); ++v) {
      const float x = sheet.positions[3 * v], y = sheet.positions[3 * v + 1];
      const float hover = (std::abs(x) < 0.15f && std::abs(y) < 0.15f) ? 1.0f : 0.0f;
      sheet.overlays[v].fixed = sheet.overlays[v].handle = hover;
    }
    const MeshId mesh = renderer.add_mesh(sheet);
    const TextureRGBA8 image = sheet_image(context, renderer, mesh, unlit_displacement());
    const auto hover = pixel(image, kSize / 2, kSize / 2);
    EXPECT_GT(hover.r, hover.g + 80) << "magenta";
    EXPECT_GT(hover.b, hover.g + 80) << "magenta";
    const auto map = pixel(image, kSize / 2 + kSize / 4, kSize / 2);
    EXPECT_GT(map.r, map.b + 80) << "the map's red";
    // The dragged handle (handle alone) on the displacement map: magenta too, not the red that reads as the
    // legend's largest move.
    RenderMesh dragged = sheet;
    for (auto& overlay : dragged.overlays) overlay.fixed = 0.0f;
    const TextureRGBA8 drag_image =
        sheet_image(context, renderer, renderer.add_mesh(dragged), unlit_displacement());
    const auto handle = pixel(drag_image, kSize / 2, kSize / 2);
    EXPECT_GT(handle.r, handle.g + 80) << "magenta";
    EXPECT_GT(handle.b, handle.g + 80) << "magenta";
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

class StereoTest : public ::testing::TestWithParam<VkSampleCountFlagBits> {};

TEST_P(StereoTest, TwoLayersAndTwoImagesAgree) {
  Context context = make_context();
  {
    RendererOptions options;
    options.samples = GetParam();
    Renderer renderer(context, options);
    RenderMesh sphere = make_sphere(1.0f, 32, 64);
    sphere.submeshes.push_back({0, uint32_t(sphere.indices.size()), int(renderer.add_material(red_paint()))});
    const MeshId mesh = renderer.add_mesh(sphere);
    const auto eyes = stereo_pair(sphere_view(), 0.4f);
    const Draw draw{mesh, glm::mat4(1.0f)};

    OffscreenTarget layered(context, kSize, kSize, 2);
    renderer.render(eyes, std::span(&draw, 1), FrameSettings{}, layered.targets());
    const TextureRGBA8 left = layered.read_back(0), right = layered.read_back(1);

    OffscreenTarget left_image(context, kSize, kSize), right_image(context, kSize, kSize);
    RenderTargets pair = left_image.targets();
    pair.views.push_back(right_image.layer_target(0));
    renderer.render(eyes, std::span(&draw, 1), FrameSettings{}, pair);
    const TextureRGBA8 left2 = left_image.read_back(), right2 = right_image.read_back();
    if (compare_images(right, right2, 0).differing_pixels != 0) {
      write_png(testing::output_dir() / "stereo_layer_left.png", left);
      write_png(testing::output_dir() / "stereo_layer_right.png", right);
      write_png(testing::output_dir() / "stereo_image_left.png", left2);
      write_png(testing::output_dir() / "stereo_image_right.png", right2);
    }
    EXPECT_EQ(compare_images(left, left2, 0).differing_pixels, 0u);
    EXPECT_EQ(compare_images(right, right2, 0).differing_pixels, 0u);
    EXPECT_GT(compare_images(left, right, 8).differing_pixels, 100u)
        << "the eyes should see different images";
    if (GetParam() == VK_SAMPLE_COUNT_4_BIT)
      testing::expect_matches_reference(left, "sphere_stereo_left", 8, 64);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}
INSTANTIATE_TEST_SUITE_P(Samples, StereoTest,
                         ::testing::Values(VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT));

TEST(Renderer, RendersWithHandedInDevice) {
  // Stands in for the XR runtime: someone else creates the instance and device, the renderer borrows.
  Context owner = make_context();
  {
    ExternalVulkan external{owner.instance(), owner.physical_device(), owner.device(),
                            owner.queue_family_index(), owner.queue()};
    Context borrowed = Context::wrap(external);
    EXPECT_FALSE(borrowed.owns_device());
    Renderer renderer(borrowed);
    RenderMesh sphere = make_sphere(1.0f, 48, 96);
    sphere.submeshes.push_back({0, uint32_t(sphere.indices.size()), int(renderer.add_material(red_paint()))});
    const MeshId mesh = renderer.add_mesh(sphere);
    OffscreenTarget target(borrowed, kSize, kSize);
    const View view = sphere_view();
    const Draw draw{mesh, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&draw, 1), FrameSettings{}, target.targets());
    testing::expect_matches_reference(target.read_back(), "sphere_material", 8, 64);
  }
  EXPECT_EQ(owner.validation_message_count(), 0u);
}

TEST(Renderer, StreamedPositionsMatchAStaticUploadOfTheSameMesh) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh flat = make_sheet(64);
    const RenderMesh bent = bump_on(flat);
    const MeshId streamed = renderer.add_mesh(flat, true);
    const MeshId reference = renderer.add_mesh(bent, false);
    OffscreenTarget target(context, kSize, kSize);
    View view = testing::sheet_camera();
    view.view = glm::lookAt(glm::vec3(0.0f, -2.5f, 2.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    FrameSettings settings;
    settings.color_mode = ColorMode::displacement;
    settings.up = {0.0f, 0.0f, 1.0f};

    // Several frames in flight, each with new positions (the last ones are `bent`).
    for (int frame = 0; frame < 5; ++frame) {
      std::vector<float> positions = bent.positions;
      const float s = float(frame + 1) / 5.0f;
      for (size_t v = 0; v < bent.vertex_count(); ++v) positions[3 * v + 2] *= s;
      std::vector<float> scalars(bent.scalars);
      for (float& x : scalars) x *= s;
      renderer.update_vertices(streamed, positions, compute_vertex_normals(positions, bent.indices), scalars);
      const Draw draw{streamed, glm::mat4(1.0f)};
      renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
      EXPECT_EQ(renderer.last_upload_bytes(), 7u * bent.vertex_count() * sizeof(float));
    }
    const TextureRGBA8 streamed_image = target.read_back();
    const Draw draw{reference, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    const ImageComparison cmp = compare_images(streamed_image, target.read_back(), 1);
    EXPECT_EQ(cmp.differing_pixels, 0u);
    testing::expect_matches_reference(streamed_image, "sheet_bump_displacement", 8, 64);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// Zero copy: a producer thread writes shapes into the mesh's VertexStream and publishes them while the render
// thread keeps frames in flight; the image after the last one equals a static upload of the same data, with
// no upload recorded. Overlays given to update_vertices draw over the bound set; positions, normals and
// scalars given to update_vertices win over a set published before them.
TEST(Renderer, ZeroCopyStreamedSetsMatchAStaticUploadOfTheSameMesh) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh flat = make_sheet(64);
    const RenderMesh bent = bump_on(flat);
    RenderMesh marked = bent;
    marked.overlays.resize(marked.vertex_count());
    for (size_t v = 0; v < marked.vertex_count(); ++v) {
      const float x = marked.positions[3 * v];
      marked.overlays[v] = {1.0f, x > 0.5f ? 1.0f : 0.0f, std::abs(x) < 0.2f ? 1.0f : 0.0f};
    }
    const MeshId streamed = renderer.add_mesh(flat, true);
    const MeshId reference = renderer.add_mesh(bent, false);
    const MeshId marked_reference = renderer.add_mesh(marked, false);
    const std::shared_ptr<VertexStream> stream = renderer.vertex_stream(streamed);
    ASSERT_NE(stream, nullptr);  // lavapipe: all its memory is device local and host visible
    EXPECT_EQ(renderer.vertex_stream(reference), nullptr);
    EXPECT_EQ(stream->vertex_count(), bent.vertex_count());
    OffscreenTarget target(context, kSize, kSize);
    View view = testing::sheet_camera();
    view.view = glm::lookAt(glm::vec3(0.0f, -2.5f, 2.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    FrameSettings settings;
    settings.color_mode = ColorMode::displacement;
    settings.up = {0.0f, 0.0f, 1.0f};
    auto draw_and_read = [&](MeshId mesh) {
      const Draw draw{mesh, glm::mat4(1.0f)};
      renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
      return target.read_back();
    };
    auto fill = [&](VertexStream::Lease& set, float s) {
      std::vector<float> positions = bent.positions;
      for (size_t v = 0; v < bent.vertex_count(); ++v) positions[3 * v + 2] *= s;
      const std::vector<float> normals = compute_vertex_normals(positions, bent.indices);
      std::copy(positions.begin(), positions.end(), set.positions().begin());
      std::copy(normals.begin(), normals.end(), set.normals().begin());
      for (size_t v = 0; v < bent.vertex_count(); ++v) set.scalars()[v] = bent.scalars[v] * s;
    };

    constexpr int kShapes = 40;  // the last is `bent`
    std::atomic<bool> done{false};
    std::thread producer([&] {
      for (int k = 1; k <= kShapes; ++k) {
        VertexStream::Lease set;
        while (!(set = stream->acquire()))
          std::this_thread::yield();  // every set in use: the next frame frees one
        fill(set, float(k) / kShapes);
        stream->publish(std::move(set));
        if (k % 4 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      done = true;
    });
    const Draw draw{streamed, glm::mat4(1.0f)};
    int frames = 0;
    while (!done || frames < 6) {  // frames in flight: render() does not wait for the GPU
      renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
      EXPECT_EQ(renderer.last_upload_bytes(), 0u);
      ++frames;
    }
    producer.join();
    const TextureRGBA8 streamed_image = draw_and_read(streamed);
    EXPECT_EQ(compare_images(streamed_image, draw_and_read(reference), 0).differing_pixels, 0u);
    testing::expect_matches_reference(streamed_image, "sheet_bump_displacement", 8, 64);

    // Sets in use go back once their frames are done; a lease dropped unpublished goes back at once.
    std::vector<VertexStream::Lease> leases;
    while (VertexStream::Lease set = stream->acquire()) leases.push_back(std::move(set));
    EXPECT_GE(leases.size(), stream->set_count() - 2);  // the current set, maybe one retiring
    const size_t free_sets = leases.size();
    leases.clear();
    while (VertexStream::Lease set = stream->acquire()) leases.push_back(std::move(set));
    EXPECT_EQ(leases.size(), free_sets);
    leases.clear();

    // Overlays alone: drawn over the bound set.
    renderer.update_vertices(streamed, {}, {}, {}, marked.overlays);
    const TextureRGBA8 marked_image = draw_and_read(streamed);
    EXPECT_EQ(renderer.last_upload_bytes(), 3u * marked.vertex_count() * sizeof(float));
    EXPECT_EQ(compare_images(marked_image, draw_and_read(marked_reference), 0).differing_pixels, 0u);

    // A flat set published, then update_vertices with the bent data: the later one (the mesh's own buffers).
    VertexStream::Lease set = stream->acquire();
    ASSERT_TRUE(set);
    fill(set, 0.0f);
    stream->publish(std::move(set));
    renderer.update_vertices(streamed, bent.positions, bent.normals, bent.scalars);
    EXPECT_EQ(compare_images(draw_and_read(streamed), marked_image, 0).differing_pixels, 0u);
    // And a set published after it wins again.
    set = stream->acquire();
    ASSERT_TRUE(set);
    fill(set, 0.5f);
    stream->publish(std::move(set));
    EXPECT_GT(compare_images(draw_and_read(streamed), marked_image, 8).differing_pixels, 100u);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// A renderer without zero copy has no stream: the staging copies only.
TEST(Renderer, ZeroCopyStreamingCanBeTurnedOff) {
  Context context = make_context();
  {
    RendererOptions options;
    options.zero_copy_streaming = false;
    Renderer renderer(context, options);
    EXPECT_EQ(renderer.vertex_stream(renderer.add_mesh(make_sheet(8), true)), nullptr);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// Eyes and a mirror window of another size in one loop: the renderer keeps a depth/MSAA set per size, so
// alternating targets (and more sizes than it keeps, which drops the least recently used) gives exactly the
// images each target gets alone.
TEST(Renderer, TargetsOfSeveralSizesAlternateAndEachMatchesItsImageAlone) {
  Context context = make_context();
  {
    const std::array<uint32_t, 6> sizes{256, 160, 96, 200, 128, 72};
    std::vector<TextureRGBA8> alone;
    const View view = sphere_view();
    {
      Renderer renderer(context);
      const MeshId sphere = renderer.add_mesh(make_sphere(1.0f, 24, 48));
      const Draw draw{sphere, glm::mat4(1.0f)};
      for (uint32_t size : sizes) {
        Renderer single(context);
        const MeshId own = single.add_mesh(make_sphere(1.0f, 24, 48));
        const Draw own_draw{own, glm::mat4(1.0f)};
        OffscreenTarget target(context, size, size);
        single.render(std::span(&view, 1), std::span(&own_draw, 1), FrameSettings{}, target.targets());
        alone.push_back(target.read_back());
      }
      std::vector<OffscreenTarget> targets;
      for (uint32_t size : sizes) targets.emplace_back(context, size, size);
      for (int round = 0; round < 2; ++round)
        for (size_t i = 0; i < sizes.size(); ++i)
          renderer.render(std::span(&view, 1), std::span(&draw, 1), FrameSettings{}, targets[i].targets());
      for (size_t i = 0; i < sizes.size(); ++i)
        EXPECT_EQ(compare_images(targets[i].read_back(), alone[i], 0).differing_pixels, 0u) << sizes[i];
    }
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// The review's handle / region / fixed highlight changes with every drag: overlays streamed into a mesh
// draw exactly like the same overlays uploaded with the mesh.
TEST(Renderer, StreamedOverlaysMatchAStaticUploadOfTheSameOverlays) {
  Context context = make_context();
  {
    Renderer renderer(context);
    RenderMesh plain = make_sheet(32);
    RenderMesh marked = plain;
    marked.overlays.resize(marked.vertex_count());
    for (size_t v = 0; v < marked.vertex_count(); ++v) {
      const float x = marked.positions[3 * v];
      marked.overlays[v] = {1.0f, x > 0.5f ? 1.0f : 0.0f, std::abs(x) < 0.2f ? 1.0f : 0.0f};
    }
    const MeshId streamed = renderer.add_mesh(plain, true);
    const MeshId reference = renderer.add_mesh(marked, false);
    OffscreenTarget target(context, kSize, kSize);
    View view = testing::sheet_camera();
    FrameSettings settings;
    settings.up = {0.0f, 0.0f, 1.0f};
    const Draw before{streamed, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&before, 1), settings, target.targets());
    const TextureRGBA8 unmarked = target.read_back();
    renderer.update_vertices(streamed, plain.positions, {}, {}, marked.overlays);
    renderer.render(std::span(&view, 1), std::span(&before, 1), settings, target.targets());
    EXPECT_EQ(renderer.last_upload_bytes(),
              6u * marked.vertex_count() * sizeof(float));  // positions + overlays
    const TextureRGBA8 streamed_image = target.read_back();
    const Draw draw{reference, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    EXPECT_EQ(compare_images(streamed_image, target.read_back(), 0).differing_pixels, 0u);
    EXPECT_GT(compare_images(streamed_image, unmarked, 8).differing_pixels, 1000u);  // the overlays show
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

TEST(Renderer, LegendIsDrawnInTheCorner) {
  Context context = make_context();
  {
    Renderer renderer(context);
    const MeshId mesh = renderer.add_mesh(make_sheet(8));
    renderer.set_legend(make_displacement_legend(25.0f, "|d| mm", 160, 320), {0.02f, 0.5f, 0.3f, 0.98f});
    OffscreenTarget target(context, kSize, kSize);
    const View view = testing::sheet_camera();
    const Draw draw{mesh, glm::mat4(1.0f)};
    FrameSettings settings;
    settings.color_mode = ColorMode::displacement;
    renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    const TextureRGBA8 image = target.read_back();
    testing::expect_matches_reference(image, "legend", 8, 64);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

// A legend changes during a drag (its top follows |d|): the old one is retired, not waited for, while frames
// are in flight; many changes between two frames drain the queue. The last legend set is the one drawn, and
// the validation layer sees no image or descriptor set freed while in use.
TEST(Renderer, ALegendChangedWhileFramesAreInFlightShowsTheNewOne) {
  Context context = make_context();
  {
    Renderer renderer(context);
    const MeshId mesh = renderer.add_mesh(make_sheet(8));
    OffscreenTarget target(context, kSize, kSize);
    const View view = testing::sheet_camera();
    const Draw draw{mesh, glm::mat4(1.0f)};
    FrameSettings settings;
    settings.color_mode = ColorMode::displacement;
    const glm::vec4 rect{0.02f, 0.5f, 0.3f, 0.98f};
    for (int k = 0; k < 12; ++k) {  // no read-back between frames: they stay in flight
      renderer.set_legend(make_displacement_legend(k % 2 ? 50.0f : 10.0f, "|d| mm", 160, 320), rect);
      renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    }
    for (int k = 0; k < 10; ++k)  // no frame between: more retired than the renderer keeps
      renderer.set_legend(make_displacement_legend(float(k + 1), "|d| mm", 160, 320), rect);
    renderer.set_legend(std::nullopt);
    renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    renderer.set_legend(make_displacement_legend(25.0f, "|d| mm", 160, 320), rect);
    renderer.render(std::span(&view, 1), std::span(&draw, 1), settings, target.targets());
    testing::expect_matches_reference(target.read_back(), "legend", 8, 64);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

TEST(Renderer, RejectsMalformedMeshes) {
  Context context = make_context();
  Renderer renderer(context);
  RenderMesh bad = make_sheet(2);
  bad.indices.push_back(999);
  bad.indices.push_back(0);
  bad.indices.push_back(1);
  EXPECT_THROW(renderer.add_mesh(bad), std::invalid_argument);
  RenderMesh short_normals = make_sheet(2);
  short_normals.normals.pop_back();
  EXPECT_THROW(renderer.add_mesh(short_normals), std::invalid_argument);
  const MeshId fixed_mesh = renderer.add_mesh(make_sheet(2));
  const std::vector<float> positions(27, 0.0f);
  EXPECT_THROW(renderer.update_vertices(fixed_mesh, positions), std::invalid_argument);
}

}  // namespace
}  // namespace pushpull::renderer

namespace pushpull::renderer {
namespace {

// The default material (a model without materials, e.g. OFF/OBJ/PLY) must stand out from the
// background everywhere on a lit sphere, its shadowed side included: every pixel of the sphere's
// disc differs from the clear colour by at least 40, 99% of them by 50 (8-bit sRGB, Euclidean over RGB;
// the blue-grey default it replaces matched the background exactly on the shadowed side).
TEST(Renderer, DefaultMaterialStandsOutFromTheBackground) {
  Context context = make_context();
  TextureRGBA8 image;
  {
    Renderer renderer(context);
    RenderMesh sphere = make_sphere(1.0f, 48, 96);
    sphere.submeshes.push_back({0, uint32_t(sphere.indices.size()), -1});  // -1: the default material
    const MeshId mesh = renderer.add_mesh(sphere);
    OffscreenTarget target(context, kSize, kSize);
    const View view = sphere_view();
    const Draw draw{mesh, glm::mat4(1.0f)};
    renderer.render(std::span(&view, 1), std::span(&draw, 1), FrameSettings{}, target.targets());
    image = target.read_back();
  }
  write_png(testing::output_dir() / "default_material.png", image);  // for inspection
  const glm::ivec3 background = encoded(glm::vec3(FrameSettings{}.clear_colour));
  const glm::vec2 centre(0.5f * float(kSize));
  // The sphere's disc: the first pixel along the row through the centre that is not the background.
  int edge = 0;
  while (edge < int(kSize) / 2) {
    const auto p = pixel(image, uint32_t(edge), kSize / 2);
    if (std::abs(int(p.r) - background.r) + std::abs(int(p.g) - background.g) +
            std::abs(int(p.b) - background.b) >
        6)
      break;
    ++edge;
  }
  const float radius = centre.x - float(edge) - 3.0f;  // inside the anti-aliased rim
  ASSERT_GT(radius, 30.0f);
  std::vector<float> distances;
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      if (glm::length(glm::vec2(float(x) + 0.5f, float(y) + 0.5f) - centre) > radius) continue;
      const auto p = pixel(image, x, y);
      distances.push_back(glm::length(glm::vec3(
          float(int(p.r) - background.r), float(int(p.g) - background.g), float(int(p.b) - background.b))));
    }
  std::sort(distances.begin(), distances.end());
  const double closest = distances.front(), first_percentile = distances[distances.size() / 100];
  std::printf(
      "default material: disc radius %.0f px; sphere pixels differ from the background by at least %.1f "
      "(1st percentile %.1f, median %.1f)\n",
      double(radius), closest, first_percentile, double(distances[distances.size() / 2]));
  EXPECT_GE(closest, 40.0);
  EXPECT_GE(first_percentile, 50.0);
}

}  // namespace
}  // namespace pushpull::renderer
