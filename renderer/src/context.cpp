// Instance/device creation (or adoption of external handles) for the renderer.
#include "pushpull/renderer/context.hpp"

#include "pushpull/renderer/vk_check.hpp"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::renderer {
namespace {
struct MessageSink {
  std::atomic<uint32_t> count{0};
  bool print = true;
};
}  // namespace

struct Context::State {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family_index = 0;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  bool owns = false;
  MessageSink sink;

  ~State() {
    if (!owns) return;
    if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
    if (messenger != VK_NULL_HANDLE) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy != nullptr) destroy(instance, messenger, nullptr);
    }
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
  }
};

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user) {
  auto* sink = static_cast<MessageSink*>(user);
  sink->count.fetch_add(1);
  if (sink->print) {
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::fprintf(stderr, "pushpull renderer: validation %s: %s\n", level, data->pMessage);
  }
  return VK_FALSE;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  PP_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  PP_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

// Prefers a discrete, then integrated GPU, then anything (lavapipe) with Vulkan 1.3 and graphics.
VkPhysicalDevice pick_physical_device(VkInstance instance, uint32_t& family) {
  uint32_t count = 0;
  PP_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  PP_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  VkPhysicalDevice best = VK_NULL_HANDLE;
  int best_score = -1;
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(candidate, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) continue;
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, families.data());
    for (uint32_t i = 0; i < family_count; ++i) {
      if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0) continue;
      int score = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 3
                  : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2
                                                                               : 1;
      if (score > best_score) {
        best_score = score;
        best = candidate;
        family = i;
      }
      break;
    }
  }
  if (best == VK_NULL_HANDLE)
    throw VulkanError(
        VK_ERROR_INITIALIZATION_FAILED,
        "no Vulkan 1.3 physical device with a graphics queue (is mesa-vulkan-drivers installed?)");
  return best;
}

}  // namespace

void Context::require_features(VkPhysicalDeviceVulkan13Features& features13) {
  features13.dynamicRendering = VK_TRUE;
  features13.synchronization2 = VK_TRUE;
}

Context Context::create(const ContextOptions& options) {
  auto state = std::make_unique<State>();
  state->owns = true;
  state->sink.print = options.print_validation_messages;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (const auto& e : options.instance_extensions) extensions.push_back(e.c_str());
  const char* validation_layer = "VK_LAYER_KHRONOS_validation";
  if (options.validation) {
    if (!has_layer(validation_layer))
      throw VulkanError(VK_ERROR_LAYER_NOT_PRESENT,
                        "validation requested but VK_LAYER_KHRONOS_validation is not installed "
                        "(Debian: vulkan-validationlayers)");
    layers.push_back(validation_layer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }

  VkApplicationInfo app{};

  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.application_name.c_str();
  app.pEngineName = "pushpull";
  app.apiVersion = VK_API_VERSION_1_3;

  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};

  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = on_validation_message;
  messenger_info.pUserData = &state->sink;

  VkInstanceCreateInfo instance_info{};

  instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  instance_info.pApplicationInfo = &app;
  instance_info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  instance_info.ppEnabledLayerNames = layers.data();
  instance_info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  instance_info.ppEnabledExtensionNames = extensions.data();
  if (options.validation) instance_info.pNext = &messenger_info;  // also covers create/destroy
  PP_VK_CHECK(vkCreateInstance(&instance_info, nullptr, &state->instance));

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(state->instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr)
      throw VulkanError(VK_ERROR_EXTENSION_NOT_PRESENT, "vkCreateDebugUtilsMessengerEXT not available");
    PP_VK_CHECK(create(state->instance, &messenger_info, nullptr, &state->messenger));
  }

  state->physical_device = pick_physical_device(state->instance, state->queue_family_index);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = state->queue_family_index;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkPhysicalDeviceVulkan13Features features13{};

  features13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  require_features(features13);
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &features13;

  std::vector<const char*> device_extensions;
  if (options.swapchain) device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

  VkDeviceCreateInfo device_info{};

  device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device_info.pNext = &features;
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.enabledExtensionCount = static_cast<uint32_t>(device_extensions.size());
  device_info.ppEnabledExtensionNames = device_extensions.data();
  PP_VK_CHECK(vkCreateDevice(state->physical_device, &device_info, nullptr, &state->device));
  vkGetDeviceQueue(state->device, state->queue_family_index, 0, &state->queue);
  vkGetPhysicalDeviceProperties(state->physical_device, &state->properties);
  vkGetPhysicalDeviceMemoryProperties(state->physical_device, &state->memory);
  return Context(std::move(state));
}

Context Context::wrap(const ExternalVulkan& external) {
  if (external.instance == VK_NULL_HANDLE || external.physical_device == VK_NULL_HANDLE ||
      external.device == VK_NULL_HANDLE || external.queue == VK_NULL_HANDLE)
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "Context::wrap: a handed-in Vulkan handle is null");
  auto state = std::make_unique<State>();
  state->owns = false;
  state->instance = external.instance;
  state->physical_device = external.physical_device;
  state->device = external.device;
  state->queue = external.queue;
  state->queue_family_index = external.queue_family_index;
  vkGetPhysicalDeviceProperties(state->physical_device, &state->properties);
  vkGetPhysicalDeviceMemoryProperties(state->physical_device, &state->memory);
  if (state->properties.apiVersion < VK_API_VERSION_1_3)
    throw VulkanError(VK_ERROR_INCOMPATIBLE_DRIVER, "Context::wrap: the handed-in device is not Vulkan 1.3");
  return Context(std::move(state));
}

Context::Context(std::unique_ptr<State> state) : state_(std::move(state)) {}
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;
Context::~Context() = default;

VkInstance Context::instance() const {
  return state_->instance;
}
VkPhysicalDevice Context::physical_device() const {
  return state_->physical_device;
}
VkDevice Context::device() const {
  return state_->device;
}
VkQueue Context::queue() const {
  return state_->queue;
}
uint32_t Context::queue_family_index() const {
  return state_->queue_family_index;
}
const VkPhysicalDeviceProperties& Context::properties() const {
  return state_->properties;
}
bool Context::owns_device() const {
  return state_->owns;
}
uint32_t Context::validation_message_count() const {
  return state_->sink.count.load();
}

uint32_t Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < state_->memory.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (state_->memory.memoryTypes[i].propertyFlags & required) == required)
      return i;
  throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY, "no memory type with the required properties");
}

}  // namespace pushpull::renderer
