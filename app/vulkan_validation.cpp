#include "vulkan_validation.hpp"

#include <cstdio>

#include <stdexcept>
#include "pushpull/xr/runtime_calls.hpp"

namespace pushpull::app {

std::vector<std::string> validation_layers() { return {"VK_LAYER_KHRONOS_validation"}; }
std::vector<std::string> validation_extensions() { return {VK_EXT_DEBUG_UTILS_EXTENSION_NAME}; }

VulkanValidation::VulkanValidation(VkInstance instance) : instance_(instance) {
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  if (create == nullptr)
    throw std::runtime_error("Vulkan validation: VK_EXT_debug_utils is not enabled on the runtime's instance");
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &VulkanValidation::callback;
  info.pUserData = this;
  const VkResult r = create(instance, &info, nullptr, &messenger_);
  if (r != VK_SUCCESS)
    throw std::runtime_error("vkCreateDebugUtilsMessengerEXT failed with VkResult " + std::to_string(int(r)));
}

VulkanValidation::~VulkanValidation() {
  auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
  if (destroy != nullptr && messenger_ != VK_NULL_HANDLE) destroy(instance_, messenger_, nullptr);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanValidation::callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                          VkDebugUtilsMessageTypeFlagsEXT,
                                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                          void* user) {
  auto* self = static_cast<VulkanValidation*>(user);
  const bool runtime = xr::inside_runtime_call() || std::this_thread::get_id() != self->owner_;
  (runtime ? self->runtime_count_ : self->count_).fetch_add(1);
  std::fprintf(stderr, "vulkan validation %s%s: %s\n",
               (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning",
               runtime ? " (inside the OpenXR runtime's work)" : "",
               data && data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

}  // namespace pushpull::app
