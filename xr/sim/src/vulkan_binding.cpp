// XR_KHR_vulkan_enable and XR_KHR_vulkan_enable2: graphics requirements, the physical device the
// runtime wants, and (enable2) creating the application's VkInstance and VkDevice from its create-info.
#include "dispatch.hpp"
#include "vulkan_util.hpp"

#include <cstring>
#include <string>
#include <vector>

namespace pushpull::xrsim {

XrResult bind_vulkan(const Instance& instance, const void* next, VulkanBinding* out) {
  const XrGraphicsBindingVulkanKHR* binding = nullptr;
  for (auto* h = static_cast<const XrBaseInStructure*>(next); h != nullptr; h = h->next)
    if (h->type == XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR)
      binding = reinterpret_cast<const XrGraphicsBindingVulkanKHR*>(h);
  if (binding == nullptr) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  if (!instance.vk_requirements_queried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
  if (binding->instance == VK_NULL_HANDLE || binding->physicalDevice == VK_NULL_HANDLE ||
      binding->device == VK_NULL_HANDLE)
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  // XR_KHR_vulkan_enable: the application must have enabled the extensions the runtime named (Vulkan
  // returns no function of an extension that was not enabled): one of each list is checked.
  if (Config::from_env().vulkan1_only &&
      (vkGetInstanceProcAddr(binding->instance, "vkGetPhysicalDeviceFeatures2KHR") == nullptr ||
       vkGetDeviceProcAddr(binding->device, "vkGetMemoryFdKHR") == nullptr))
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(binding->physicalDevice, &families, nullptr);
  if (binding->queueFamilyIndex >= families) return XR_ERROR_VALIDATION_FAILURE;
  VulkanBinding vk;
  vk.instance = binding->instance;
  vk.physical_device = binding->physicalDevice;
  vk.device = binding->device;
  vk.queue_family = binding->queueFamilyIndex;
  vk.queue_index = binding->queueIndex;
  vkGetDeviceQueue(vk.device, vk.queue_family, vk.queue_index, &vk.queue);
  VkCommandPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool.queueFamilyIndex = vk.queue_family;
  if (vkCreateCommandPool(vk.device, &pool, nullptr, &vk.pool) != VK_SUCCESS)
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  *out = vk;
  return XR_SUCCESS;
}

void release_vulkan(VulkanBinding& vk) {
  if (vk.pool != VK_NULL_HANDLE) vkDestroyCommandPool(vk.device, vk.pool, nullptr);
  vk.pool = VK_NULL_HANDLE;
}

VkResult submit_and_wait(const VulkanBinding& vk, const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = vk.pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  VkResult r = vkAllocateCommandBuffers(vk.device, &alloc, &cb);
  if (r != VK_SUCCESS) return r;
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cb, &begin);
  record(cb);
  vkEndCommandBuffer(cb);
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence = VK_NULL_HANDLE;
  r = vkCreateFence(vk.device, &fence_info, nullptr, &fence);
  if (r == VK_SUCCESS) {
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cb;
    r = vkQueueSubmit(vk.queue, 1, &submit, fence);
    if (r == VK_SUCCESS) r = vkWaitForFences(vk.device, 1, &fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(vk.device, fence, nullptr);
  }
  vkFreeCommandBuffers(vk.device, vk.pool, 1, &cb);
  return r;
}

uint32_t find_memory_type(VkPhysicalDevice device, uint32_t type_bits, VkMemoryPropertyFlags properties) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(device, &mp);
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) != 0 && (mp.memoryTypes[i].propertyFlags & properties) == properties)
      return i;
  return UINT32_MAX;
}

namespace {

XrResult check_instance_system(XrInstance handle, XrSystemId system, Instance** out) {
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  *out = instance;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_requirements(XrInstance handle, XrSystemId system,
                                     XrGraphicsRequirementsVulkanKHR* req) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_instance_system(handle, system, &instance); XR_FAILED(r)) return r;
  if (req == nullptr || req->type != XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN_KHR)
    return XR_ERROR_VALIDATION_FAILURE;
  req->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
  req->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
  instance->vk_requirements_queried = true;
  return XR_SUCCESS;
}

// XR_KHR_vulkan_enable: the Vulkan extensions the application must enable, space-separated. The
// compositor needs none, but a runtime that shares images across processes asks for these (SteamVR on Linux
// names a similar set), so the application's parsing and enabling of them is exercised; lavapipe has them.
constexpr const char* kInstanceExtensions =
    "VK_KHR_external_memory_capabilities VK_KHR_get_physical_device_properties2";
constexpr const char* kDeviceExtensions =
    "VK_KHR_external_memory VK_KHR_external_memory_fd VK_KHR_get_memory_requirements2 "
    "VK_KHR_dedicated_allocation";

XrResult extensions_for(XrInstance handle, XrSystemId system, const char* names, uint32_t capacity,
                        uint32_t* count, char* buffer) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_instance_system(handle, system, &instance); XR_FAILED(r)) return r;
  return two_call_string(names, capacity, count, buffer);
}

XrResult XRAPI_CALL get_instance_extensions(XrInstance handle, XrSystemId system, uint32_t capacity,
                                            uint32_t* count, char* buffer) {
  // unknown-vk-extension: also one no Vulkan driver has (the application must say which).
  const std::string names = std::string(kInstanceExtensions) +
                            (Config::from_env().unknown_vk_extension ? " VK_PUSHPULL_sim_unknown" : "");
  return extensions_for(handle, system, names.c_str(), capacity, count, buffer);
}

XrResult XRAPI_CALL get_device_extensions(XrInstance handle, XrSystemId system, uint32_t capacity,
                                          uint32_t* count, char* buffer) {
  // unknown-vk-device-extension: also one no Vulkan driver has.
  const std::string names =
      std::string(kDeviceExtensions) +
      (Config::from_env().unknown_vk_device_extension ? " VK_PUSHPULL_sim_unknown_device" : "");
  return extensions_for(handle, system, names.c_str(), capacity, count, buffer);
}

// The physical device the runtime composites on: PUSHPULL_XR_SIM_VK_DEVICE names one, else the
// first GPU with a graphics queue, else the first device (lavapipe on a machine without a GPU).
VkPhysicalDevice choose_physical_device(const Config& config, VkInstance vk_instance,
                                        PFN_vkGetInstanceProcAddr gipa) {
  auto enumerate =
      reinterpret_cast<PFN_vkEnumeratePhysicalDevices>(gipa(vk_instance, "vkEnumeratePhysicalDevices"));
  auto properties =
      reinterpret_cast<PFN_vkGetPhysicalDeviceProperties>(gipa(vk_instance, "vkGetPhysicalDeviceProperties"));
  auto families = reinterpret_cast<PFN_vkGetPhysicalDeviceQueueFamilyProperties>(
      gipa(vk_instance, "vkGetPhysicalDeviceQueueFamilyProperties"));
  if (enumerate == nullptr || properties == nullptr || families == nullptr) return VK_NULL_HANDLE;
  uint32_t n = 0;
  if (enumerate(vk_instance, &n, nullptr) != VK_SUCCESS || n == 0) return VK_NULL_HANDLE;
  std::vector<VkPhysicalDevice> devices(n);
  enumerate(vk_instance, &n, devices.data());
  VkPhysicalDevice cpu = VK_NULL_HANDLE;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    properties(d, &p);
    if (!config.vk_device.empty()) {
      if (std::strstr(p.deviceName, config.vk_device.c_str()) != nullptr) return d;
      continue;
    }
    uint32_t qn = 0;
    families(d, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> q(qn);
    families(d, &qn, q.data());
    bool graphics = false;
    for (const auto& f : q) graphics = graphics || (f.queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
    if (!graphics) continue;
    if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
      if (cpu == VK_NULL_HANDLE) cpu = d;
    } else {
      return d;
    }
  }
  return cpu;
}

XrResult XRAPI_CALL get_graphics_device(XrInstance handle, XrSystemId system, VkInstance vk_instance,
                                        VkPhysicalDevice* device) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_instance_system(handle, system, &instance); XR_FAILED(r)) return r;
  if (vk_instance == VK_NULL_HANDLE || device == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *device = choose_physical_device(instance->config, vk_instance, vkGetInstanceProcAddr);
  return *device != VK_NULL_HANDLE ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
}

XrResult XRAPI_CALL get_graphics_device2(XrInstance handle, const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                         VkPhysicalDevice* device) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || device == nullptr || info->type != XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR ||
      info->vulkanInstance == VK_NULL_HANDLE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  *device = choose_physical_device(instance->config, info->vulkanInstance, vkGetInstanceProcAddr);
  return *device != VK_NULL_HANDLE ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
}

XrResult XRAPI_CALL create_vulkan_instance(XrInstance handle, const XrVulkanInstanceCreateInfoKHR* info,
                                           VkInstance* vk_instance, VkResult* vk_result) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || vk_instance == nullptr || vk_result == nullptr ||
      info->type != XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR || info->pfnGetInstanceProcAddr == nullptr ||
      info->vulkanCreateInfo == nullptr || info->createFlags != 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  auto create = reinterpret_cast<PFN_vkCreateInstance>(
      info->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
  if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
  *vk_result = create(info->vulkanCreateInfo, info->vulkanAllocator, vk_instance);
  if (*vk_result == VK_SUCCESS) instance->vk_instance_created = *vk_instance;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_vulkan_device(XrInstance handle, const XrVulkanDeviceCreateInfoKHR* info,
                                         VkDevice* vk_device, VkResult* vk_result) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || vk_device == nullptr || vk_result == nullptr ||
      info->type != XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR || info->pfnGetInstanceProcAddr == nullptr ||
      info->vulkanCreateInfo == nullptr || info->vulkanPhysicalDevice == VK_NULL_HANDLE ||
      info->createFlags != 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  // Through the application's vkGetInstanceProcAddr on the instance the runtime made for it; otherwise
  // (an instance the application made itself) through the Vulkan loader this library links, which
  // dispatches on the physical device.
  PFN_vkCreateDevice create = nullptr;
  if (instance->vk_instance_created != VK_NULL_HANDLE)
    create = reinterpret_cast<PFN_vkCreateDevice>(
        info->pfnGetInstanceProcAddr(instance->vk_instance_created, "vkCreateDevice"));
  if (create == nullptr) create = vkCreateDevice;
  *vk_result = create(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator, vk_device);
  return XR_SUCCESS;
}

}  // namespace

void add_vulkan_functions(FunctionTable& t) {
  const char* e1 = XR_KHR_VULKAN_ENABLE_EXTENSION_NAME;
  const char* e2 = XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME;
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanGraphicsRequirementsKHR, get_requirements, e1);
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanInstanceExtensionsKHR, get_instance_extensions, e1);
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanDeviceExtensionsKHR, get_device_extensions, e1);
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanGraphicsDeviceKHR, get_graphics_device, e1);
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanGraphicsRequirements2KHR, get_requirements, e2);
  PUSHPULL_XR_ADD_EXT(t, xrGetVulkanGraphicsDevice2KHR, get_graphics_device2, e2);
  PUSHPULL_XR_ADD_EXT(t, xrCreateVulkanInstanceKHR, create_vulkan_instance, e2);
  PUSHPULL_XR_ADD_EXT(t, xrCreateVulkanDeviceKHR, create_vulkan_device, e2);
}

}  // namespace pushpull::xrsim
