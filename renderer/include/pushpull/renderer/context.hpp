// pushpull::renderer::Context: the Vulkan 1.3 instance, physical device, device and graphics queue
// the renderer draws with.
//
// Two ways to get one:
//  - Context::create(options): creates its own instance and device (headless: no surface extension
//    unless asked; on a machine without a GPU the loader finds Mesa lavapipe). With
//    options.validation it enables VK_LAYER_KHRONOS_validation and counts every message.
//  - Context::wrap(external): borrows handles created by someone else (the XR runtime, through
//    XR_KHR_vulkan_enable2). The Context then never destroys them; the caller keeps them alive
//    longer than the Context and everything created from it. The device must have been created
//    with the features listed by require_features() enabled (dynamicRendering, synchronization2).
//
// Ownership: move-only; owns only what it created. Thread-safety: the renderer records and
// submits from one thread; Context itself is immutable after creation except the message
// counter (atomic).
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pushpull::renderer {

struct ContextOptions {
  bool validation = false;                       // enable VK_LAYER_KHRONOS_validation + messenger
  bool print_validation_messages = true;         // also print each message to stderr
  std::vector<std::string> instance_extensions;  // e.g. from glfwGetRequiredInstanceExtensions
  bool swapchain = false;                        // enable VK_KHR_swapchain on the device
  std::string application_name = "pushpull";
};

// Handles created elsewhere (not owned). queue must belong to queue_family_index and support graphics.
struct ExternalVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family_index = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

class Context {
 public:
  static Context create(const ContextOptions& options = {});
  static Context wrap(const ExternalVulkan& external);

  // Adds what the renderer needs to a device-creation feature chain: call before vkCreateDevice /
  // xrCreateVulkanDeviceKHR on a device the renderer will be handed.
  static void require_features(VkPhysicalDeviceVulkan13Features& features13);

  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  ~Context();

  [[nodiscard]] VkInstance instance() const;
  [[nodiscard]] VkPhysicalDevice physical_device() const;
  [[nodiscard]] VkDevice device() const;
  [[nodiscard]] VkQueue queue() const;
  [[nodiscard]] uint32_t queue_family_index() const;
  [[nodiscard]] const VkPhysicalDeviceProperties& properties() const;
  [[nodiscard]] bool owns_device() const;

  // Validation messages (warnings and errors) seen since creation; 0 when validation is off.
  [[nodiscard]] uint32_t validation_message_count() const;

  // Memory type index with the bits in type_bits and all of `required`; throws VulkanError if none.
  [[nodiscard]] uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;

 private:
  struct State;
  explicit Context(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace pushpull::renderer
