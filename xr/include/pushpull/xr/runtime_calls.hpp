// Which thread is inside an OpenXR call of ours. A runtime records and submits Vulkan work on the device it
// shares with the application inside some calls (xrBeginFrame, xrEndFrame,
// xrAcquire/Wait/ReleaseSwapchainImage, swapchain and session creation): the Vulkan validation layer's
// messages from there are the runtime's, not pushpull's (app/vulkan_validation.hpp tells them apart with
// inside_runtime_call()).
//
// Every OpenXR call made through PUSHPULL_XR_CHECK (xr_check.hpp) and the Session's own checked calls are
// inside a RuntimeCallScope. Thread-safety: the depth is per thread.
#pragma once

namespace pushpull::xr {

class RuntimeCallScope {
 public:
  RuntimeCallScope();
  ~RuntimeCallScope();
  RuntimeCallScope(const RuntimeCallScope&) = delete;
  RuntimeCallScope& operator=(const RuntimeCallScope&) = delete;
};

// Whether the calling thread is inside an OpenXR call made in a RuntimeCallScope.
[[nodiscard]] bool inside_runtime_call();

}  // namespace pushpull::xr
