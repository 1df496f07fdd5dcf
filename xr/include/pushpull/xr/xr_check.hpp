// Checked OpenXR calls: every call of the session, swapchain and input code goes through
// PUSHPULL_XR_CHECK, which throws XrError naming the failing expression, its file:line and the result
// (XR_ERROR_SESSION_LOST, ...) when the call fails (success codes such as XR_SESSION_LOSS_PENDING pass).
//
// The OpenXR headers need Vulkan's types first (XR_USE_GRAPHICS_API_VULKAN): include this header
// rather than <openxr/openxr_platform.h> directly.
// Thread-safety: free functions without state.
#pragma once

#define XR_USE_GRAPHICS_API_VULKAN
#include <vulkan/vulkan.h>

#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <stdexcept>
#include <string>

#include "pushpull/xr/runtime_calls.hpp"

namespace pushpull::xr {

// A failed OpenXR call. what(): "file:line: expr failed with XR_ERROR_... (-n)".
class XrError : public std::runtime_error {
 public:
  XrError(const std::string& message, XrResult result) : std::runtime_error(message), result_(result) {}
  [[nodiscard]] XrResult result() const { return result_; }

 private:
  XrResult result_;
};

// "XR_ERROR_SESSION_LOST" (through xrResultToString when an instance is given, else the number).
[[nodiscard]] std::string result_name(XrInstance instance, XrResult result);

// "VK_ERROR_EXTENSION_NOT_PRESENT (-7)" for the results creating a Vulkan instance or device can give, else
// "VkResult n".
[[nodiscard]] std::string vk_result_name(VkResult result);

// Throws XrError when XR_FAILED(result); returns result otherwise (it may be a success code).
XrResult check_xr(XrResult result, XrInstance instance, const char* expression, const char* file, int line);

}  // namespace pushpull::xr

// `instance` may be XR_NULL_HANDLE (before xrCreateInstance): the result is then printed as a number.
// The call runs inside a RuntimeCallScope (runtime_calls.hpp): the temporary lives to the end of the
// full expression.
#define PUSHPULL_XR_CHECK(instance, expression)                                                         \
  ::pushpull::xr::check_xr((::pushpull::xr::RuntimeCallScope{}, (expression)), (instance), #expression, \
                           __FILE__, __LINE__)
