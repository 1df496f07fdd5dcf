// renderer_bench: frame time of a stereo frame (2 x 1440 x 1600 by default) of a procedural mesh of
// about 110K triangles (ToyCar's count), and the extra cost of streaming a full deformed position +
// normal buffer every frame. Runs on whatever Vulkan device the loader picks (lavapipe without a GPU).
// For ToyCar itself: `pushpull render ToyCar.gltf --stereo 0.064 --size 1440 1600 --benchmark N`.
//
// Usage: renderer_bench [FRAMES=10] [WIDTH=1440] [HEIGHT=1600] [SAMPLES=1]
#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/offscreen_target.hpp"
#include "pushpull/renderer/renderer.hpp"

#include <glm/gtc/constants.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

using namespace pushpull::renderer;

namespace {

RenderMesh wavy_sphere(int stacks, int slices) {
  RenderMesh m;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j) {
      const float theta = glm::pi<float>() * float(i) / float(stacks);
      const float phi = glm::two_pi<float>() * float(j) / float(slices);
      const float r = 1.0f + 0.05f * std::sin(7.0f * phi) * std::sin(5.0f * theta);
      m.positions.insert(m.positions.end(), {r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                                             r * std::sin(theta) * std::sin(phi)});
      m.scalars.push_back(0.5f + 0.5f * std::cos(theta));
    }
  const auto row = uint32_t(slices + 1);
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const uint32_t a = uint32_t(i) * row + uint32_t(j), b = a + row;
      m.indices.insert(m.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  m.normals = compute_vertex_normals(m.positions, m.indices);
  return m;
}

}  // namespace

int main(int argc, char** argv) try {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 10;
  const uint32_t width = argc > 2 ? uint32_t(std::atoi(argv[2])) : 1440;
  const uint32_t height = argc > 3 ? uint32_t(std::atoi(argv[3])) : 1600;
  const int samples = argc > 4 ? std::atoi(argv[4]) : 1;
  if (frames <= 0 || width == 0 || height == 0) {
    std::fprintf(stderr, "usage: renderer_bench [FRAMES] [WIDTH] [HEIGHT] [SAMPLES]\n");
    return 2;
  }
  Context context = Context::create();
  VkPhysicalDeviceProperties props = context.properties();
  RendererOptions options;
  options.samples = VkSampleCountFlagBits(samples);
  Renderer renderer(context, options);
  const RenderMesh mesh = wavy_sphere(166, 332);
  const MeshId id = renderer.add_mesh(mesh, true);
  OffscreenTarget target(context, width, height, 2);
  const auto eyes = stereo_pair(
      frame_bounds(compute_bounds(mesh.positions), OrbitCamera{}, float(width) / float(height)), 0.064f);
  const Draw draw{id, glm::mat4(1.0f)};
  FrameSettings settings;

  std::vector<float> positions = mesh.positions;
  std::vector<float> normals(positions.size());
  double normals_ms = 0.0;
  using Clock = std::chrono::steady_clock;
  auto run = [&](bool upload, std::span<const Draw> draws) {
    renderer.render(eyes, draws, settings, target.targets());
    renderer.wait_idle();
    normals_ms = 0.0;
    const auto start = Clock::now();
    for (int f = 0; f < frames; ++f) {
      if (upload) {
        for (float& x : positions) x *= (f % 2 == 0) ? 1.0001f : 1.0f / 1.0001f;
        const auto t0 = Clock::now();
        compute_vertex_normals(positions, mesh.indices, normals);
        normals_ms += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        renderer.update_vertices(id, positions, normals);
      }
      renderer.render(eyes, draws, settings, target.targets());
    }
    renderer.wait_idle();
    normals_ms /= frames;
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count() / frames;
  };
  const std::span<const Draw> draws(&draw, 1);
  const double plain = run(false, draws);
  const double streamed = run(true, draws);
  const double streamed_normals = normals_ms;
  const double empty = run(false, {});
  const double empty_upload = run(true, {});
  std::printf(
      "device: %s; %zu triangles, %u vertices; stereo 2 x %ux%u, %dx MSAA, %d frames per measurement\n",
      props.deviceName, mesh.indices.size() / 3, mesh.vertex_count(), width, height, samples, frames);
  std::printf("frame time, no upload:                    %9.2f ms\n", plain);
  std::printf("frame time, full upload each frame:       %9.2f ms (includes CPU normals %.2f ms)\n", streamed,
              streamed_normals);
  std::printf("upload cost isolated (empty frames):      %9.2f ms (%.2f MB positions + normals)\n",
              empty_upload - empty, double(renderer.last_upload_bytes()) / 1e6);
  std::printf("CPU normal recomputation:                 %9.2f ms\n", normals_ms);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "renderer_bench: %s\n", e.what());
  return 1;
}
