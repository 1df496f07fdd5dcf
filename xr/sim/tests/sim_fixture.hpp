// Test support: an OpenXR instance on the simulated runtime through the real OpenXR loader
// (XR_RUNTIME_JSON points at the manifest the build wrote), a Vulkan device made through
// XR_KHR_vulkan_enable2 on lavapipe, sessions and frames. Not thread-safe; one per test.
#pragma once

#define XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_TIMESPEC
// Vulkan first: openxr_platform.h uses its types.
#include <vulkan/vulkan.h>

#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <string>
#include <vector>

namespace sim_test {

// Throws std::runtime_error naming the expression, file:line and result when `r` is not `expected`.
void check(XrResult r, XrResult expected, const char* expr, const char* file, int line);
#define XRC(expr) ::sim_test::check((expr), XR_SUCCESS, #expr, __FILE__, __LINE__)

// Points the loader at the simulated runtime and Vulkan at lavapipe; clears the runtime's env knobs.
void use_simulated_runtime();
// Writes `text` to a fresh file under the test's temporary folder and returns its path.
std::string write_temp_file(const std::string& name, const std::string& text);
std::string temp_dir(const std::string& name);

class Sim {
 public:
  explicit Sim(std::vector<const char*> extensions = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
                                                      XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME,
                                                      XR_EXT_CONFORMANCE_AUTOMATION_EXTENSION_NAME});
  ~Sim();
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  template <class Pfn>
  Pfn fn(const char* name) {
    PFN_xrVoidFunction f = nullptr;
    XRC(xrGetInstanceProcAddr(instance, name, &f));
    return reinterpret_cast<Pfn>(f);
  }
  XrPath path(const char* s);

  // Vulkan instance + device through XR_KHR_vulkan_enable2, then a session on them.
  XrSession create_session();
  // Polls events; returns the session states seen, in order.
  std::vector<XrSessionState> poll_states();
  // Polls to READY and begins the session (PRIMARY_STEREO).
  void begin_session();
  // wait + begin + end (no layers); returns the predicted display time.
  XrTime frame();
  XrSpace reference_space(XrReferenceSpaceType type);

  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  XrSession session = XR_NULL_HANDLE;
  VkInstance vk_instance = VK_NULL_HANDLE;
  VkPhysicalDevice vk_physical = VK_NULL_HANDLE;
  VkDevice vk_device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  std::vector<XrEventDataBuffer> other_events;  // non-state events seen by poll_states()
};

}  // namespace sim_test
