// pushpull::renderer::Renderer: draws meshes with glTF materials or review colour maps into one or
// two views per frame (mono, or stereo into two images / two layers), and streams new vertex
// positions every frame.
//
// Colour maps and overlays read RenderMesh::scalars / overlays; FrameSettings picks the mode.
//
// Usage per frame (one thread):
//   renderer.update_vertices(mesh, positions, normals);   // optional: copies into a staging ring slot
//   renderer.render(views, draws, settings, targets);      // records uploads + both views, submits
//
// Streaming: each mesh created with streamed = true owns frames_in_flight host-visible staging
// slots. update_vertices() memcpys into the slot of the frame being built (waiting only for the GPU
// to finish the frame that used that slot frames_in_flight frames ago, never for the current one);
// render() records a copy into the device-local vertex buffer before drawing, behind a barrier that
// waits for earlier frames' vertex reads (no CPU stall; the GPU serialises copy and previous draw).
// Zero copy (VertexStream, vertex_stream()): where the device has memory that is both device local and host
// visible (lavapipe, integrated GPUs, ReBAR), a streamed mesh also has a ring of vertex sets bound directly
// as its positions, normals and scalars: a producer thread writes the next shape into a free set and
// publishes it, each frame draws the newest published set, and nothing is copied on the frame's thread.
// update_vertices() with positions, normals or scalars switches the mesh back to its own buffers (give all
// three then); overlays alone leave the stream's sets bound.
// Normals are recomputed on the CPU by the caller, on the thread that produced the positions
// (compute_vertex_normals in geometry.hpp: O(#V + #T), measured 0.8 ms for 110K triangles on one
// core, up to 7 ms on a loaded 2-core machine), or passed empty to keep the previous ones. A GPU
// compute pass would avoid the CPU cost but needs the vertex-face adjacency on the GPU; not done.
//
// Targets: images owned by someone else (OffscreenTarget, XR swapchain images, a window swapchain).
// The renderer owns the depth and multisample buffers: one set per target size and format in use (up to
// four; eyes and a mirror window of another size alternate without a GPU wait), the least recently used
// dropped (after vkDeviceWaitIdle) when a fifth size appears.
//
// Ownership: borrows the Context (must outlive the Renderer). Thread-safety: not thread-safe; every
// call must come from the thread that constructed it (asserted).
#pragma once

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/types.hpp"
#include "pushpull/renderer/vertex_stream.hpp"

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace pushpull::renderer {

using TextureId = uint32_t;
using MaterialId = uint32_t;
using MeshId = uint32_t;

// One colour image (or one layer of an array image) a view renders into.
struct ColorTarget {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  // a 2D view of exactly that layer, mip 0
  uint32_t layer = 0;
  // Layout the image is in when render() is called (UNDEFINED: contents are discarded, which they
  // are anyway: the renderer clears) and the layout it leaves it in.
  VkImageLayout initial_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageLayout final_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
};

struct RenderTargets {
  VkExtent2D extent{};
  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;  // colour format of every view (shaders write linear)
  std::vector<ColorTarget> views;             // 1 (mono) or 2 (left, right), same size as `views`
};

// Optional synchronisation with a swapchain or XR compositor.
struct FrameSync {
  VkSemaphore wait = VK_NULL_HANDLE;    // waited before colour output (e.g. swapchain acquire)
  VkSemaphore signal = VK_NULL_HANDLE;  // signalled when the frame is done (e.g. present)
};

// A mesh placed in the world for one frame.
struct Draw {
  MeshId mesh = 0;
  glm::mat4 T_world_mesh{1.0f};
  bool colour_mapped = true;  // false: always its material (arrows, section curves), no overlays
  bool on_top = false;        // drawn after the rest without depth test (the p0 -> p1 arrow)
};

// One pass of a loop frame: views into targets (the headset's eyes, or a window), with its own draws, settings
// and synchronisation. The spans and the targets must stay valid during render_frame().
struct RenderPass {
  std::span<const View> views;
  std::span<const Draw> draws;
  FrameSettings settings;
  const RenderTargets* targets = nullptr;
  FrameSync sync;
  // Instead of drawing the scene: copy this image (a colour target drawn by an earlier pass of the same
  // frame, left in COLOR_ATTACHMENT_OPTIMAL, which it is again afterwards) into the one target, scaled to
  // cover it and centred (a mirror window showing an eye as it is); then `draws`, if any, over the copy with
  // views[0] (exactly one view then), in order, one sample, without depth test (a HUD), and the legend when
  // the settings show it. The source needs TRANSFER_SRC usage and the target TRANSFER_DST (can_blit() says
  // whether the formats allow it).
  const ColorTarget* blit_from = nullptr;
  VkExtent2D blit_from_extent{};
};

struct RendererOptions {
  // Loop frames (render or render_frame calls) the CPU may run ahead of the GPU; each owns a staging slot.
  uint32_t frames_in_flight = 2;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;  // MSAA, resolved into the targets
  // Streamed meshes get a VertexStream where the memory allows it (false: the staging copies only).
  bool zero_copy_streaming = true;
};

class Renderer {
 public:
  // Throws std::invalid_argument for frames_in_flight 0 or a sample count that is not one the device renders
  // colour and depth targets with (lavapipe: 1 and 4), naming the counts it has.
  Renderer(const Context& context, const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Textures and materials are immutable once added. Material texture fields hold TextureIds.
  TextureId add_texture(const TextureRGBA8& texture);
  MaterialId add_material(const Material& material);

  // Uploads a mesh (normals computed when empty). streamed: positions/normals/scalars will change.
  // Submesh material indices are MaterialIds (-1: the default grey).
  MeshId add_mesh(const RenderMesh& mesh, bool streamed = false);

  // New vertex data for a streamed mesh, applied by the next render(). positions: #V*3; normals:
  // #V*3 or empty (keep); scalars: #V or empty (keep); overlays: #V or empty (keep). Throws
  // std::invalid_argument on a size
  // mismatch or a mesh not created streamed.
  void update_vertices(MeshId mesh, std::span<const float> positions, std::span<const float> normals = {},
                       std::span<const float> scalars = {}, std::span<const OverlayWeights> overlays = {});

  // The zero-copy stream of a streamed mesh (see VertexStream), or null: not streamed, or the device has no
  // memory both device local and host visible, or RendererOptions::zero_copy_streaming is off. Every Lease of
  // it must be gone before the Renderer is destroyed.
  [[nodiscard]] std::shared_ptr<VertexStream> vertex_stream(MeshId mesh) const;

  // A screen-space legend (e.g. make_displacement_legend) drawn in every view at rect (x0, y0, x1,
  // y1 in 0..1, y down); std::nullopt removes it.
  void set_legend(std::optional<TextureRGBA8> legend, glm::vec4 rect = {0.02f, 0.70f, 0.30f, 0.97f});

  // Records and submits one frame: pending uploads, then views.size() views (1 or 2) into
  // targets.views. Returns without waiting for the GPU.
  void render(std::span<const View> views, std::span<const Draw> draws, const FrameSettings& settings,
              const RenderTargets& targets, const FrameSync& sync = {});

  // One loop frame of several passes (at most kMaxPasses: the eyes and a mirror window), recorded and submitted
  // together: one frame in flight and one staging slot for all of them, the vertex uploads recorded once before
  // the first pass. Each pass is its own batch of the one submission (a window's acquire semaphore holds back
  // only its pass); the frame's fence covers all. render() is render_frame() with one pass.
  static constexpr size_t kMaxPasses = 2;
  // Whether an image of format `from` can be blitted, linearly filtered, into one of format `to`.
  [[nodiscard]] bool can_blit(VkFormat from, VkFormat to) const;
  void render_frame(std::span<const RenderPass> passes);

  // Waits until the GPU has finished everything submitted.
  void wait_idle();

  // Bytes copied by the uploads recorded in the last render() (benchmarks).
  [[nodiscard]] uint64_t last_upload_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::renderer
