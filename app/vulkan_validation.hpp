// Counting Vulkan validation messages on an instance someone else created (the XR runtime's, through
// XR_KHR_vulkan_enable2): a VK_EXT_debug_utils messenger that prints each warning and error to stderr.
// The instance needs VK_LAYER_KHRONOS_validation and VK_EXT_debug_utils enabled (validation_layers() and
// validation_extensions() name them).
// Messages are told apart by where they come from: inside an OpenXR call of ours (xr::inside_runtime_call:
// the runtime's own Vulkan work on the shared device, e.g. SteamVR's in xrEndFrame) or from a thread other
// than the one that made this (the runtime's threads) count as the runtime's; the others are pushpull's.
// Ownership: owns the messenger; borrows the instance (outlives this). Thread-safety: the counters are atomic
// (the layer may call from any thread); construct and destroy on one thread, the frame loop's.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace pushpull::app {

std::vector<std::string> validation_layers();      // {"VK_LAYER_KHRONOS_validation"}
std::vector<std::string> validation_extensions();  // {"VK_EXT_debug_utils"}

class VulkanValidation {
 public:
  // Throws std::runtime_error naming the problem when the messenger cannot be created.
  explicit VulkanValidation(VkInstance instance);
  ~VulkanValidation();
  VulkanValidation(const VulkanValidation&) = delete;
  VulkanValidation& operator=(const VulkanValidation&) = delete;

  [[nodiscard]] uint32_t message_count() const { return count_.load(); }  // pushpull's
  [[nodiscard]] uint32_t runtime_message_count() const { return runtime_count_.load(); }

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT types,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  VkInstance instance_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::atomic<uint32_t> count_{0}, runtime_count_{0};
  std::thread::id owner_ = std::this_thread::get_id();
};

}  // namespace pushpull::app
