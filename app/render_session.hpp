// The Vulkan side of `pushpull render` and of the replay report's pictures: a context and renderer kept for
// several pictures of one model (PictureRenderer), and render_to_png, one picture to a PNG (optionally with a
// benchmark of frames and streaming uploads).
// Thread-safety: call from one thread (the renderer asserts it).
#pragma once

#include "render_inputs.hpp"

#include "pushpull/renderer/types.hpp"

#include <filesystem>
#include <memory>

namespace pushpull::app {

// One Vulkan context and renderer for the pictures of one render model: its textures and materials are
// uploaded once and the model's mesh once, as a streamed mesh whose vertices each picture replaces (lavapipe
// compiles its pipelines once, not per picture). Each picture with an arrow or section curves adds their
// small meshes (the renderer keeps every mesh it was given until it is destroyed).
class PictureRenderer {
 public:
  // samples: MSAA (1, 2, 4 or 8); validation: VK_LAYER_KHRONOS_validation (messages counted).
  // Throws std::runtime_error (and Vulkan errors) when no device can be created.
  PictureRenderer(std::shared_ptr<const RenderModel> render, int samples, bool validation);
  ~PictureRenderer();
  PictureRenderer(const PictureRenderer&) = delete;
  PictureRenderer& operator=(const PictureRenderer&) = delete;

  // One picture (RGBA8, rows top to bottom; with options.ipd the two eyes side by side, left | right) of
  // inputs, whose render model must be this renderer's, at options.size with its camera, colour map, legend
  // and lighting. Throws CommandError on a bad camera or a foreign render model.
  [[nodiscard]] renderer::TextureRGBA8 render(const RenderInputs& inputs,
                                              const RenderCommandOptions& options);
  // Prints frame times for options.benchmark_frames frames (after a render() of the same inputs and options):
  // plain, uploading full positions and normals every frame, and the upload alone.
  void benchmark(const RenderInputs& inputs, const RenderCommandOptions& options);
  // Destroys the renderer (waiting for the GPU; render() and benchmark() throw after it) and returns the
  // messages the validation layer reported, its destruction included (0 without validation).
  std::size_t close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes a picture as PNG through a temporary file and rename (a crash never leaves half a file); throws
// CommandError naming the file on failure.
void write_picture(const std::filesystem::path& path, const renderer::TextureRGBA8& image);

// Renders and writes options.out; throws CommandError naming the file on failure.
void render_to_png(const RenderInputs& inputs, const RenderCommandOptions& options);

}  // namespace pushpull::app
