// pushpull::renderer::OffscreenTarget: colour images the renderer draws into without a window
// (headless rendering, tests, PNG output). layers = 2 gives one array image with a layer per eye.
// Ownership: owns its image; borrows the Context. Thread-safety: one thread.
#pragma once

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/renderer/types.hpp"

#include <memory>

namespace pushpull::renderer {

class OffscreenTarget {
 public:
  OffscreenTarget(const Context& context, uint32_t width, uint32_t height, uint32_t layers = 1,
                  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB);
  ~OffscreenTarget();
  OffscreenTarget(OffscreenTarget&&) noexcept;
  OffscreenTarget& operator=(OffscreenTarget&&) noexcept;

  // Targets for render(): layer i for view i; left in TRANSFER_SRC_OPTIMAL for readback.
  [[nodiscard]] RenderTargets targets() const;
  // One layer as a ColorTarget (to combine two single-layer targets into a stereo pair).
  [[nodiscard]] ColorTarget layer_target(uint32_t layer) const;

  // Waits for the queue to go idle and copies one layer back (RGBA8, rows top to bottom). Call after
  // render() into this target.
  [[nodiscard]] TextureRGBA8 read_back(uint32_t layer = 0) const;

  [[nodiscard]] VkExtent2D extent() const;
  [[nodiscard]] VkFormat format() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::renderer
