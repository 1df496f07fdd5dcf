#include "sim_fixture.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace sim_test {

void check(XrResult r, XrResult expected, const char* expr, const char* file, int line) {
  if (r != expected)
    throw std::runtime_error(std::string(file) + ":" + std::to_string(line) + ": " + expr + " returned " +
                             std::to_string(r) + ", expected " + std::to_string(expected));
}

void use_simulated_runtime() {
  setenv("XR_RUNTIME_JSON", PUSHPULL_XR_SIM_MANIFEST, 1);
  const char* lvp = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
  if (std::filesystem::exists(lvp)) setenv("VK_ICD_FILENAMES", lvp, 1);
  for (const char* v : {"PUSHPULL_XR_SIM_INPUT", "PUSHPULL_XR_SIM_CAPTURE", "PUSHPULL_XR_SIM_CAPTURE_EVERY",
                        "PUSHPULL_XR_SIM_PROFILE", "PUSHPULL_XR_SIM_WIDTH", "PUSHPULL_XR_SIM_HEIGHT",
                        "PUSHPULL_XR_SIM_RATE", "PUSHPULL_XR_SIM_HAPTICS", "XR_ENABLE_API_LAYERS"})
    unsetenv(v);
}

std::string temp_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "pushpull_xr_sim_tests" /
                              (std::string(info->test_suite_name()) + "." + info->name()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::string write_temp_file(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::path(temp_dir("files_" + name)) / name).string();
  std::ofstream(path) << text;
  return path;
}

Sim::Sim(std::vector<const char*> extensions) {
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "xr_sim_test");
  ci.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.enabledExtensionNames = extensions.data();
  XRC(xrCreateInstance(&ci, &instance));
  XrSystemGetInfo si{XR_TYPE_SYSTEM_GET_INFO};
  si.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XRC(xrGetSystem(instance, &si, &system));
}

Sim::~Sim() {
  if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
  if (vk_device != VK_NULL_HANDLE) vkDestroyDevice(vk_device, nullptr);
  if (vk_instance != VK_NULL_HANDLE) vkDestroyInstance(vk_instance, nullptr);
}

XrPath Sim::path(const char* s) {
  XrPath p = XR_NULL_PATH;
  XRC(xrStringToPath(instance, s, &p));
  return p;
}

XrSession Sim::create_session() {
  auto requirements = fn<PFN_xrGetVulkanGraphicsRequirements2KHR>("xrGetVulkanGraphicsRequirements2KHR");
  auto create_instance = fn<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR");
  auto get_device = fn<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR");
  auto create_device = fn<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR");
  XrGraphicsRequirementsVulkan2KHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
  XRC(requirements(instance, system, &req));

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "xr_sim_test";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo vci{};
  vci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  vci.pApplicationInfo = &app;
  XrVulkanInstanceCreateInfoKHR xci{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
  xci.systemId = system;
  xci.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
  xci.vulkanCreateInfo = &vci;
  VkResult vr = VK_ERROR_UNKNOWN;
  XRC(create_instance(instance, &xci, &vk_instance, &vr));
  if (vr != VK_SUCCESS) throw std::runtime_error("vkCreateInstance through the runtime failed");

  XrVulkanGraphicsDeviceGetInfoKHR gi{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
  gi.systemId = system;
  gi.vulkanInstance = vk_instance;
  XRC(get_device(instance, &gi, &vk_physical));

  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(vk_physical, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(vk_physical, &n, families.data());
  for (uint32_t i = 0; i < n; ++i)
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
      queue_family = i;
      break;
    }
  const float priority = 1.f;
  VkDeviceQueueCreateInfo qci{};
  qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qci.queueFamilyIndex = queue_family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{};
  dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  XrVulkanDeviceCreateInfoKHR xdci{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
  xdci.systemId = system;
  xdci.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
  xdci.vulkanPhysicalDevice = vk_physical;
  xdci.vulkanCreateInfo = &dci;
  XRC(create_device(instance, &xdci, &vk_device, &vr));
  if (vr != VK_SUCCESS) throw std::runtime_error("vkCreateDevice through the runtime failed");

  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  binding.instance = vk_instance;
  binding.physicalDevice = vk_physical;
  binding.device = vk_device;
  binding.queueFamilyIndex = queue_family;
  binding.queueIndex = 0;
  XrSessionCreateInfo sci{XR_TYPE_SESSION_CREATE_INFO};
  sci.next = &binding;
  sci.systemId = system;
  XRC(xrCreateSession(instance, &sci, &session));
  return session;
}

std::vector<XrSessionState> Sim::poll_states() {
  std::vector<XrSessionState> states;
  for (;;) {
    XrEventDataBuffer e{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult r = xrPollEvent(instance, &e);
    if (r == XR_EVENT_UNAVAILABLE) break;
    XRC(r);
    if (e.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
      states.push_back(reinterpret_cast<XrEventDataSessionStateChanged&>(e).state);
    else
      other_events.push_back(e);
  }
  return states;
}

void Sim::begin_session() {
  poll_states();
  XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO};
  bi.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  XRC(xrBeginSession(session, &bi));
}

XrTime Sim::frame() {
  XrFrameState fs{XR_TYPE_FRAME_STATE};
  XRC(xrWaitFrame(session, nullptr, &fs));
  XRC(xrBeginFrame(session, nullptr));
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.displayTime = fs.predictedDisplayTime;
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  XRC(xrEndFrame(session, &ei));
  return fs.predictedDisplayTime;
}

XrSpace Sim::reference_space(XrReferenceSpaceType type) {
  XrReferenceSpaceCreateInfo ci{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
  ci.referenceSpaceType = type;
  ci.poseInReferenceSpace.orientation.w = 1.f;
  XrSpace space = XR_NULL_HANDLE;
  XRC(xrCreateReferenceSpace(session, &ci, &space));
  return space;
}

}  // namespace sim_test

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
