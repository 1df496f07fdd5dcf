// Vulkan plumbing on the application's device: the session's graphics binding, one-shot command
// submission on the application's queue, memory types. The application externally synchronizes its
// queue with xrCreateSwapchain / xrEndFrame (OpenXR spec, XR_KHR_vulkan_enable), which is where these
// are used; callers hold big_lock().
#pragma once

#include "state.hpp"

#include <functional>

namespace pushpull::xrsim {

// Reads the XrGraphicsBindingVulkan(2)KHR in a session create-info `next` chain, checks it and makes
// a command pool on its queue family. Errors: XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING,
// XR_ERROR_GRAPHICS_DEVICE_INVALID, XR_ERROR_VALIDATION_FAILURE.
XrResult bind_vulkan(const Instance& instance, const void* next, VulkanBinding* out);
void release_vulkan(VulkanBinding& vk);

// Records `record` into a fresh command buffer, submits it on the session's queue and waits for it.
VkResult submit_and_wait(const VulkanBinding& vk, const std::function<void(VkCommandBuffer)>& record);

// A memory type index with `properties` among `type_bits`, or UINT32_MAX.
uint32_t find_memory_type(VkPhysicalDevice device, uint32_t type_bits, VkMemoryPropertyFlags properties);

}  // namespace pushpull::xrsim
