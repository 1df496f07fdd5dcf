// Checked Vulkan calls: every failure names the failing expression, its VkResult and file:line.
// Thread-safety: stateless.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace pushpull::renderer {

// Thrown for any failed Vulkan call or unmet device requirement. result() is VK_SUCCESS when the
// failure is not a VkResult (e.g. no suitable memory type).
class VulkanError : public std::runtime_error {
 public:
  VulkanError(VkResult result, const std::string& what) : std::runtime_error(what), result_(result) {}
  [[nodiscard]] VkResult result() const { return result_; }

 private:
  VkResult result_;
};

// Readable name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY").
const char* to_string(VkResult result);

[[noreturn]] void throw_vulkan_error(VkResult result, const char* expression, const char* file, int line);

}  // namespace pushpull::renderer

// PP_VK_CHECK(vkCreateX(...)): throws VulkanError("vkCreateX(...) failed: VK_ERROR_... at file:line").
#define PP_VK_CHECK(expr)                                                                 \
  do {                                                                                    \
    const VkResult pp_vk_result_ = (expr);                                                \
    if (pp_vk_result_ != VK_SUCCESS)                                                      \
      ::pushpull::renderer::throw_vulkan_error(pp_vk_result_, #expr, __FILE__, __LINE__); \
  } while (false)
