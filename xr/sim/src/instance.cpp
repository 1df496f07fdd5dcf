// Instance, system, view configurations, paths, events and time conversion.
#include "dispatch.hpp"
#include "sim_math.hpp"

#include <openxr/openxr_reflection.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <thread>

namespace pushpull::xrsim {
namespace {

struct ExtensionInfo {
  const char* name;
  uint32_t version;
};
constexpr ExtensionInfo kExtensions[] = {
    {XR_KHR_VULKAN_ENABLE_EXTENSION_NAME, XR_KHR_vulkan_enable_SPEC_VERSION},
    {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME, XR_KHR_vulkan_enable2_SPEC_VERSION},
    {XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME, XR_KHR_convert_timespec_time_SPEC_VERSION},
    {XR_EXT_CONFORMANCE_AUTOMATION_EXTENSION_NAME, XR_EXT_conformance_automation_SPEC_VERSION},
    {XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME, XR_KHR_composition_layer_depth_SPEC_VERSION},
    // Interaction profiles beyond OpenXR 1.0's (profiles.cpp; withheld by the no-controller-extensions
    // quirk).
    {XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME, XR_EXT_hp_mixed_reality_controller_SPEC_VERSION},
    {XR_HTC_VIVE_COSMOS_CONTROLLER_INTERACTION_EXTENSION_NAME,
     XR_HTC_vive_cosmos_controller_interaction_SPEC_VERSION},
    {XR_EXT_SAMSUNG_ODYSSEY_CONTROLLER_EXTENSION_NAME, XR_EXT_samsung_odyssey_controller_SPEC_VERSION},
};

// Whether the runtime offers the extension `name` (the vulkan1-only quirk withdraws XR_KHR_vulkan_enable2,
// no-vulkan both Vulkan extensions, no-controller-extensions those that bring interaction profiles).
bool offered(const char* name) {
  const Config config = Config::from_env();
  if (config.no_controller_extensions && profile_extension(name)) return false;
  if ((config.vulkan1_only || config.no_vulkan) &&
      std::strcmp(name, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) == 0)
    return false;
  return !(config.no_vulkan && std::strcmp(name, XR_KHR_VULKAN_ENABLE_EXTENSION_NAME) == 0);
}

XrResult XRAPI_CALL enumerate_instance_extension_properties(const char* layer_name, uint32_t capacity,
                                                            uint32_t* count,
                                                            XrExtensionProperties* properties) {
  if (layer_name != nullptr && layer_name[0] != 0) return XR_ERROR_API_LAYER_NOT_PRESENT;
  if (capacity != 0 && properties == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (capacity != 0)
    for (uint32_t i = 0; i < capacity; ++i)
      if (properties[i].type != XR_TYPE_EXTENSION_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  std::vector<ExtensionInfo> listed;
  for (const auto& e : kExtensions)
    if (offered(e.name)) listed.push_back(e);
  return two_call(capacity, count, uint32_t(listed.size()), [&](uint32_t i) {
    std::snprintf(properties[i].extensionName, XR_MAX_EXTENSION_NAME_SIZE, "%s", listed[i].name);
    properties[i].extensionVersion = listed[i].version;
  });
}

XrResult XRAPI_CALL enumerate_api_layer_properties(uint32_t capacity, uint32_t* count,
                                                   XrApiLayerProperties*) {
  return two_call(capacity, count, 0, [](uint32_t) {});
}

bool supported_extension(const char* name) {
  for (const auto& e : kExtensions)
    if (std::strcmp(e.name, name) == 0) return offered(name);
  return false;
}

XrResult XRAPI_CALL create_instance(const XrInstanceCreateInfo* info, XrInstance* out) {
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_INSTANCE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->createFlags != 0) return XR_ERROR_VALIDATION_FAILURE;
  if (XR_VERSION_MAJOR(info->applicationInfo.apiVersion) != 1) return XR_ERROR_API_VERSION_UNSUPPORTED;
  if (info->applicationInfo.applicationName[0] == 0) return XR_ERROR_NAME_INVALID;
  if (info->enabledApiLayerCount != 0) return XR_ERROR_API_LAYER_NOT_PRESENT;
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i)
    if (info->enabledExtensionNames == nullptr || !supported_extension(info->enabledExtensionNames[i]))
      return XR_ERROR_EXTENSION_NOT_PRESENT;
  auto instance = std::make_unique<Instance>();
  instance->config = Config::from_env();
  instance->created = monotonic_now();
  instance->application_name = info->applicationInfo.applicationName;
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i)
    instance->extensions.insert(info->enabledExtensionNames[i]);
  if (!instance->config.input_script.empty()) {
    try {
      instance->script =
          std::make_shared<const InputScript>(InputScript::load(instance->config.input_script));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pushpull xr sim: PUSHPULL_XR_SIM_INPUT: %s\n", e.what());
      return XR_ERROR_INITIALIZATION_FAILED;
    }
  }
  Lock lock(big_lock());
  Instance* raw = instance.release();
  register_handle(raw, HandleKind::instance);
  *out = to_handle<XrInstance>(raw);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_instance(XrInstance handle) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (instance->config.hangs_on_destroy)  // quirk: never returns, as SteamVR on Linux may not
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
  while (!instance->sessions.empty()) destroy_session(instance->sessions.back());
  while (!instance->action_sets.empty()) destroy_action_set(instance->action_sets.back());
  unregister_handle(instance);
  delete instance;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_instance_properties(XrInstance handle, XrInstanceProperties* properties) {
  Lock lock(big_lock());
  const Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (properties == nullptr || properties->type != XR_TYPE_INSTANCE_PROPERTIES)
    return XR_ERROR_VALIDATION_FAILURE;
  properties->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
  std::snprintf(properties->runtimeName, XR_MAX_RUNTIME_NAME_SIZE, "%s",
                instance->config.runtime_name.c_str());
  return XR_SUCCESS;
}

XrResult XRAPI_CALL poll_event(XrInstance handle, XrEventDataBuffer* buffer) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr || buffer->type != XR_TYPE_EVENT_DATA_BUFFER) return XR_ERROR_VALIDATION_FAILURE;
  if (instance->events.empty()) return XR_EVENT_UNAVAILABLE;
  *buffer = instance->events.front();
  instance->events.pop_front();
  return XR_SUCCESS;
}

XrResult XRAPI_CALL result_to_string(XrInstance handle, XrResult value,
                                     char buffer[XR_MAX_RESULT_STRING_SIZE]) {
  Lock lock(big_lock());
  if (lookup<Instance>(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const char* name = nullptr;
  switch (value) {
#define PUSHPULL_XR_RESULT_CASE(n, v) \
  case n:                             \
    name = #n;                        \
    break;
    XR_LIST_ENUM_XrResult(PUSHPULL_XR_RESULT_CASE)
#undef PUSHPULL_XR_RESULT_CASE
        default : break;
  }
  if (name != nullptr)
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "%s", name);
  else if (XR_SUCCEEDED(value))
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_UNKNOWN_SUCCESS_%d", value);
  else
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_UNKNOWN_FAILURE_%d", -value);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL structure_type_to_string(XrInstance handle, XrStructureType value,
                                             char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
  Lock lock(big_lock());
  if (lookup<Instance>(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const char* name = nullptr;
  switch (value) {
#define PUSHPULL_XR_TYPE_CASE(n, v) \
  case n:                           \
    name = #n;                      \
    break;
    XR_LIST_ENUM_XrStructureType(PUSHPULL_XR_TYPE_CASE)
#undef PUSHPULL_XR_TYPE_CASE
        default : break;
  }
  if (name != nullptr)
    std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "%s", name);
  else
    std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d", value);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_system(XrInstance handle, const XrSystemGetInfo* info, XrSystemId* system) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || system == nullptr || info->type != XR_TYPE_SYSTEM_GET_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->formFactor == XR_FORM_FACTOR_HANDHELD_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
  if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_VALIDATION_FAILURE;
  if (monotonic_now() - instance->created < XrTime(instance->config.headset_after_ms) * 1000000 ||
      instance->headset_gone)
    return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
  instance->system_queried = true;
  *system = kSystemId;
  return XR_SUCCESS;
}

XrResult check_system(XrInstance handle, XrSystemId system, Instance** out) {
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (system != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (out != nullptr) *out = instance;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_system_properties(XrInstance handle, XrSystemId system,
                                          XrSystemProperties* properties) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_system(handle, system, &instance); XR_FAILED(r)) return r;
  if (properties == nullptr || properties->type != XR_TYPE_SYSTEM_PROPERTIES)
    return XR_ERROR_VALIDATION_FAILURE;
  properties->systemId = kSystemId;
  properties->vendorId = 0x5050;  // "PP"
  std::snprintf(properties->systemName, XR_MAX_SYSTEM_NAME_SIZE, "pushpull simulated HMD");
  properties->graphicsProperties.maxSwapchainImageWidth = 4096;
  properties->graphicsProperties.maxSwapchainImageHeight = 4096;
  properties->graphicsProperties.maxLayerCount = XR_MIN_COMPOSITION_LAYERS_SUPPORTED;
  properties->trackingProperties.orientationTracking = XR_TRUE;
  properties->trackingProperties.positionTracking = XR_TRUE;
  return XR_SUCCESS;
}

bool valid_view_configuration(XrViewConfigurationType t) {
  return t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO || t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO ||
         t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO ||
         t == XR_VIEW_CONFIGURATION_TYPE_SECONDARY_MONO_FIRST_PERSON_OBSERVER_MSFT;
}

XrResult check_view_configuration(XrViewConfigurationType t) {
  if (t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_SUCCESS;
  return valid_view_configuration(t) ? XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED
                                     : XR_ERROR_VALIDATION_FAILURE;
}

XrResult XRAPI_CALL enumerate_environment_blend_modes(XrInstance handle, XrSystemId system,
                                                      XrViewConfigurationType view_configuration,
                                                      uint32_t capacity, uint32_t* count,
                                                      XrEnvironmentBlendMode* modes) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_system(handle, system, &instance); XR_FAILED(r)) return r;
  if (const XrResult r = check_view_configuration(view_configuration); XR_FAILED(r)) return r;
  if (capacity != 0 && modes == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const XrEnvironmentBlendMode mode = instance->config.blend_mode;
  return two_call(capacity, count, 1, [&](uint32_t i) { modes[i] = mode; });
}

XrResult XRAPI_CALL enumerate_view_configurations(XrInstance handle, XrSystemId system, uint32_t capacity,
                                                  uint32_t* count, XrViewConfigurationType* types) {
  Lock lock(big_lock());
  if (const XrResult r = check_system(handle, system, nullptr); XR_FAILED(r)) return r;
  if (capacity != 0 && types == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  return two_call(capacity, count, 1,
                  [&](uint32_t i) { types[i] = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO; });
}

XrResult XRAPI_CALL get_view_configuration_properties(XrInstance handle, XrSystemId system,
                                                      XrViewConfigurationType type,
                                                      XrViewConfigurationProperties* properties) {
  Lock lock(big_lock());
  if (const XrResult r = check_system(handle, system, nullptr); XR_FAILED(r)) return r;
  if (properties == nullptr || properties->type != XR_TYPE_VIEW_CONFIGURATION_PROPERTIES)
    return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_view_configuration(type); XR_FAILED(r)) return r;
  properties->viewConfigurationType = type;
  properties->fovMutable = XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_view_configuration_views(XrInstance handle, XrSystemId system,
                                                       XrViewConfigurationType type, uint32_t capacity,
                                                       uint32_t* count, XrViewConfigurationView* views) {
  Lock lock(big_lock());
  Instance* instance = nullptr;
  if (const XrResult r = check_system(handle, system, &instance); XR_FAILED(r)) return r;
  if (const XrResult r = check_view_configuration(type); XR_FAILED(r)) return r;
  if (capacity != 0 && views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < capacity; ++i)
    if (views[i].type != XR_TYPE_VIEW_CONFIGURATION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
  const Config& c = instance->config;
  return two_call(capacity, count, 2, [&](uint32_t i) {
    const bool wider = c.eyes_differ && i == 1;
    views[i].recommendedImageRectWidth = c.width + (wider ? 16 : 0);
    views[i].recommendedImageRectHeight = c.height + (wider ? 8 : 0);
    views[i].maxImageRectWidth = 4096;
    views[i].maxImageRectHeight = 4096;
    views[i].recommendedSwapchainSampleCount = 1;
    views[i].maxSwapchainSampleCount = 1;
  });
}

// Path syntax of the OpenXR spec (section "Path Atom Type"): /component[/component...], components of
// lower-case letters, digits, '-', '_' and '.', not made only of dots.
bool well_formed_path(const char* path) {
  const std::size_t n = std::strlen(path);
  if (n == 0 || n >= XR_MAX_PATH_LENGTH || path[0] != '/' || path[n - 1] == '/') return false;
  std::size_t start = 1;
  for (std::size_t i = 1; i <= n; ++i) {
    if (i == n || path[i] == '/') {
      if (i == start) return false;  // empty component
      bool only_dots = true;
      for (std::size_t k = start; k < i; ++k) only_dots = only_dots && path[k] == '.';
      if (only_dots) return false;
      start = i + 1;
      continue;
    }
    const char c = path[i];
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.')) return false;
  }
  return true;
}

XrResult XRAPI_CALL string_to_path(XrInstance handle, const char* path_string, XrPath* path) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (path_string == nullptr || path == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (!well_formed_path(path_string)) return XR_ERROR_PATH_FORMAT_INVALID;
  *path = instance->intern(path_string);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL path_to_string(XrInstance handle, XrPath path, uint32_t capacity, uint32_t* count,
                                   char* buffer) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  const std::string* s = instance->path_string(path);
  if (s == nullptr) return XR_ERROR_PATH_INVALID;
  return two_call_string(*s, capacity, count, buffer);
}

XrResult XRAPI_CALL convert_timespec_to_time(XrInstance handle, const timespec* ts, XrTime* time) {
  Lock lock(big_lock());
  if (lookup<Instance>(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (ts == nullptr || time == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *time = static_cast<XrTime>(ts->tv_sec) * 1000000000 + ts->tv_nsec;
  if (*time <= 0) return XR_ERROR_TIME_INVALID;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL convert_time_to_timespec(XrInstance handle, XrTime time, timespec* ts) {
  Lock lock(big_lock());
  if (lookup<Instance>(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (ts == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  ts->tv_sec = static_cast<time_t>(time / 1000000000);
  ts->tv_nsec = static_cast<long>(time % 1000000000);
  return XR_SUCCESS;
}

}  // namespace

void add_instance_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrEnumerateInstanceExtensionProperties, enumerate_instance_extension_properties);
  PUSHPULL_XR_ADD(t, xrEnumerateApiLayerProperties, enumerate_api_layer_properties);
  PUSHPULL_XR_ADD(t, xrCreateInstance, create_instance);
  PUSHPULL_XR_ADD(t, xrDestroyInstance, destroy_instance);
  PUSHPULL_XR_ADD(t, xrGetInstanceProperties, get_instance_properties);
  PUSHPULL_XR_ADD(t, xrPollEvent, poll_event);
  PUSHPULL_XR_ADD(t, xrResultToString, result_to_string);
  PUSHPULL_XR_ADD(t, xrStructureTypeToString, structure_type_to_string);
  PUSHPULL_XR_ADD(t, xrGetSystem, get_system);
  PUSHPULL_XR_ADD(t, xrGetSystemProperties, get_system_properties);
  PUSHPULL_XR_ADD(t, xrEnumerateEnvironmentBlendModes, enumerate_environment_blend_modes);
  PUSHPULL_XR_ADD(t, xrEnumerateViewConfigurations, enumerate_view_configurations);
  PUSHPULL_XR_ADD(t, xrGetViewConfigurationProperties, get_view_configuration_properties);
  PUSHPULL_XR_ADD(t, xrEnumerateViewConfigurationViews, enumerate_view_configuration_views);
  PUSHPULL_XR_ADD(t, xrStringToPath, string_to_path);
  PUSHPULL_XR_ADD(t, xrPathToString, path_to_string);
  PUSHPULL_XR_ADD_EXT(t, xrConvertTimespecTimeToTimeKHR, convert_timespec_to_time,
                      XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  PUSHPULL_XR_ADD_EXT(t, xrConvertTimeToTimespecTimeKHR, convert_time_to_timespec,
                      XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
}

}  // namespace pushpull::xrsim
