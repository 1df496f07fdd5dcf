#include "pushpull/renderer/vk_check.hpp"

#include <sstream>

namespace pushpull::renderer {

const char* to_string(VkResult result) {
  switch (result) {
#define PP_CASE(x) \
  case x:          \
    return #x;
    PP_CASE(VK_SUCCESS)
    PP_CASE(VK_NOT_READY)
    PP_CASE(VK_TIMEOUT)
    PP_CASE(VK_INCOMPLETE)
    PP_CASE(VK_SUBOPTIMAL_KHR)
    PP_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    PP_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    PP_CASE(VK_ERROR_INITIALIZATION_FAILED)
    PP_CASE(VK_ERROR_DEVICE_LOST)
    PP_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    PP_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    PP_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    PP_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    PP_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    PP_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    PP_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    PP_CASE(VK_ERROR_SURFACE_LOST_KHR)
    PP_CASE(VK_ERROR_OUT_OF_DATE_KHR)
#undef PP_CASE
    default:
      return "VkResult(unknown)";
  }
}

void throw_vulkan_error(VkResult result, const char* expression, const char* file, int line) {
  std::ostringstream message;
  message << expression << " failed: " << to_string(result) << " (" << static_cast<int>(result) << ") at "
          << file << ":" << line;
  throw VulkanError(result, message.str());
}

}  // namespace pushpull::renderer
