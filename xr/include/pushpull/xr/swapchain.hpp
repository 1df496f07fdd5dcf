// pushpull::xr::Swapchain: one colour swapchain (one eye) of an OpenXR session on Vulkan, with its images.
//
// Per frame: acquire() (xrAcquireSwapchainImage + xrWaitSwapchainImage) gives the index of the image to
// render into; release() hands it back before xrEndFrame. Images arrive in COLOR_ATTACHMENT_OPTIMAL and must
// be left in that layout (XR_KHR_vulkan_enable2); the renderer's submissions go to the session's queue before
// release(), so the compositor sees them in queue order.
//
// Ownership: owns the XrSwapchain (destroyed with xrDestroySwapchain); the VkImages belong to the runtime.
// Borrows the session, which must outlive it. Thread-safety: one thread (the frame loop).
#pragma once

#include "pushpull/xr/xr_check.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace pushpull::xr {

class Swapchain {
 public:
  // A swapchain of width x height pixels, one layer, one sample, usage colour attachment, format a VkFormat
  // the runtime listed. transfer_source: also transfer source, so a mirror window can copy the eye; a runtime
  // that refuses that usage (XR_ERROR_FEATURE_UNSUPPORTED, which the spec allows for any usage bit) gets a
  // colour-attachment-only swapchain instead, and transfer_source() says false.
  Swapchain(XrInstance instance, XrSession session, int64_t format, uint32_t width, uint32_t height,
            bool transfer_source = false);
  ~Swapchain();
  Swapchain(Swapchain&&) noexcept;
  Swapchain& operator=(Swapchain&&) noexcept;

  // Acquires and waits for the next image; returns its index into images(). Throws XrError.
  uint32_t acquire();
  // Releases the image acquire() returned. No-op when nothing is acquired.
  void release();

  [[nodiscard]] XrSwapchain handle() const;
  [[nodiscard]] const std::vector<VkImage>& images() const;
  [[nodiscard]] VkFormat format() const;
  [[nodiscard]] uint32_t width() const;
  [[nodiscard]] uint32_t height() const;
  // Whether the images have transfer-source usage (a mirror may copy them).
  [[nodiscard]] bool transfer_source() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::xr
