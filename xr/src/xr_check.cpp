#include "pushpull/xr/xr_check.hpp"

#include <openxr/openxr_reflection.h>

namespace pushpull::xr {

std::string result_name(XrInstance instance, XrResult result) {
  char name[XR_MAX_RESULT_STRING_SIZE] = {};
  if (instance != XR_NULL_HANDLE && XR_SUCCEEDED(xrResultToString(instance, result, name)))
    return std::string(name) + " (" + std::to_string(int(result)) + ")";
  // No instance (xrCreateInstance failed): the names from the registry's reflection header.
  switch (result) {
#define PUSHPULL_XR_RESULT_CASE(name, value) \
  case name:                                 \
    return std::string(#name) + " (" + std::to_string(value) + ")";
    XR_LIST_ENUM_XrResult(PUSHPULL_XR_RESULT_CASE)
#undef PUSHPULL_XR_RESULT_CASE
    default:
      return "XrResult " + std::to_string(int(result));
  }
}

std::string vk_result_name(VkResult result) {
  const char* name = nullptr;
  switch (result) {
#define PUSHPULL_VK_RESULT_CASE(value) \
  case value:                          \
    name = #value;                     \
    break;
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    PUSHPULL_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
#undef PUSHPULL_VK_RESULT_CASE
    default:
      break;
  }
  return name ? std::string(name) + " (" + std::to_string(int(result)) + ")"
              : "VkResult " + std::to_string(int(result));
}

XrResult check_xr(XrResult result, XrInstance instance, const char* expression, const char* file, int line) {
  if (XR_FAILED(result))
    throw XrError(std::string(file) + ":" + std::to_string(line) + ": " + expression + " failed with " +
                      result_name(instance, result),
                  result);
  return result;
}

}  // namespace pushpull::xr
