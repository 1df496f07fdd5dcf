#include "pushpull/xr/session.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "eye_hold.hpp"
#include "finite_pose.hpp"
#include "pushpull/xr/input.hpp"

namespace pushpull::xr {
namespace {

#define CHECK(expression) PUSHPULL_XR_CHECK(instance, expression)

// Where the loader looks for the runtime, for the message when there is none.
std::string runtime_looked_for() {
  if (const char* json = std::getenv("XR_RUNTIME_JSON"); json && *json)
    return std::string("the runtime in XR_RUNTIME_JSON=") + json;
  return "the active OpenXR runtime (active_runtime.json under $XDG_CONFIG_HOME/openxr/1 or "
         "/etc/xdg/openxr/1)";
}

constexpr const char* kPointAtRuntime =
    "point at one with XR_RUNTIME_JSON=/path/to/runtime.json (the simulated runtime: "
    "XR_RUNTIME_JSON=build/xr/sim/pushpull_xr_sim.json)";

// The instance extensions the runtime lists (none when it cannot list them).
std::vector<XrExtensionProperties> offered_extensions() {
  uint32_t n = 0;
  std::vector<XrExtensionProperties> offered;
  if (XR_SUCCEEDED(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr))) {
    offered.assign(n, {XR_TYPE_EXTENSION_PROPERTIES});
    if (XR_FAILED(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, offered.data()))) n = 0;
    offered.resize(n);
  }
  return offered;
}

bool lists(const std::vector<XrExtensionProperties>& offered, const char* name) {
  return std::any_of(offered.begin(), offered.end(),
                     [&](const XrExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// The ones of `wanted` the runtime does not list (comma-separated; all of them when it lists none).
// A runtime with neither Vulkan binding is told as "XR_KHR_vulkan_enable2 (nor XR_KHR_vulkan_enable)".
std::string missing_extensions(const std::vector<XrExtensionProperties>& offered,
                               const std::vector<const char*>& wanted) {
  std::string missing;
  for (const char* name : wanted)
    if (!lists(offered, name)) {
      missing += (missing.empty() ? "" : ", ") + std::string(name);
      if (std::strcmp(name, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) == 0 &&
          !lists(offered, XR_KHR_VULKAN_ENABLE_EXTENSION_NAME))
        missing += " (nor " XR_KHR_VULKAN_ENABLE_EXTENSION_NAME ")";
    }
  return missing.empty() ? "an extension it was asked for" : missing;
}

// XR_KHR_vulkan_enable's space-separated list of the Vulkan instance or device extensions the runtime needs
// (xrGetVulkanInstanceExtensionsKHR / xrGetVulkanDeviceExtensionsKHR, which share a signature).
std::vector<std::string> runtime_vulkan_extensions(XrInstance instance, XrSystemId system,
                                                   PFN_xrGetVulkanInstanceExtensionsKHR get,
                                                   const char* call) {
  uint32_t n = 0;
  check_xr(get(instance, system, 0, &n, nullptr), instance, call, __FILE__, __LINE__);
  std::string buffer(n, '\0');
  if (n > 0) check_xr(get(instance, system, n, &n, buffer.data()), instance, call, __FILE__, __LINE__);
  buffer.resize(std::min<size_t>(buffer.size(), n));
  std::vector<std::string> names;
  std::string name;
  for (const char c : buffer + ' ') {
    if (c == ' ' || c == '\0') {
      if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      name.clear();
    } else {
      name += c;
    }
  }
  return names;
}

// Adds the names of `more` that `list` lacks (list's pointers point into `more` or the caller's strings).
void add_unique(std::vector<const char*>& list, const std::vector<std::string>& more) {
  for (const std::string& name : more)
    if (std::none_of(list.begin(), list.end(), [&](const char* e) { return name == e; }))
      list.push_back(name.c_str());
}

// The Vulkan extensions an enumerate function (a two-call vkEnumerate*ExtensionProperties for one layer,
// nullptr: the driver's and implicit layers') lists; none when it fails.
template <class Enumerate>
void append_listed(std::vector<VkExtensionProperties>& listed, Enumerate enumerate) {
  uint32_t n = 0;
  if (enumerate(&n, nullptr) != VK_SUCCESS) return;
  std::vector<VkExtensionProperties> more(n);
  if (enumerate(&n, more.data()) != VK_SUCCESS) return;
  more.resize(std::min<size_t>(n, more.size()));
  listed.insert(listed.end(), more.begin(), more.end());
}

// vkCreateInstance or vkCreateDevice (`call`, with how the runtime got there) failed with `vr`. With
// VK_ERROR_EXTENSION_NOT_PRESENT the extensions `listed` lacks are named, the runtime's (`runtime_needs`,
// XR_KHR_vulkan_enable) apart from pushpull's own (`own`): "the OpenXR runtime "R" needs Vulkan <what>
// <lacking> does not offer: ..." (RuntimeUnavailable, as the review then opens the desktop window);
// otherwise an XrError naming the call, the VkResult and `file`:`line`.
[[noreturn]] void throw_vulkan_create_failure(VkResult vr, const std::string& call, const char* file,
                                              int line, const std::vector<const char*>& own,
                                              const std::vector<std::string>& runtime_needs,
                                              const std::vector<VkExtensionProperties>& listed,
                                              const char* what, const char* lacking,
                                              const std::string& runtime_name) {
  auto absent = [&](const char* name) {
    return std::none_of(listed.begin(), listed.end(), [&](const VkExtensionProperties& e) {
      return std::strcmp(e.extensionName, name) == 0;
    });
  };
  std::string runtime_missing, own_missing;
  for (const std::string& name : runtime_needs)
    if (absent(name.c_str())) runtime_missing += (runtime_missing.empty() ? "" : ", ") + name;
  for (const char* name : own)
    if (absent(name) && std::find(runtime_needs.begin(), runtime_needs.end(), name) == runtime_needs.end())
      own_missing += (own_missing.empty() ? "" : ", ") + std::string(name);
  if (vr == VK_ERROR_EXTENSION_NOT_PRESENT && !(runtime_missing.empty() && own_missing.empty())) {
    std::string message;
    if (!runtime_missing.empty())
      message = "the OpenXR runtime \"" + runtime_name + "\" needs Vulkan " + what + " " + lacking +
                " does not offer: " + runtime_missing;
    if (!own_missing.empty())
      message += (message.empty() ? "" : "; ") + std::string("pushpull needs Vulkan ") + what + " " +
                 lacking + " does not offer: " + own_missing;
    throw RuntimeUnavailable(message + " (update the GPU driver)", XR_ERROR_RUNTIME_FAILURE);
  }
  if (vr == VK_ERROR_EXTENSION_NOT_PRESENT)  // XR_KHR_vulkan_enable2: the runtime added some out of sight
    throw RuntimeUnavailable("the OpenXR runtime \"" + runtime_name + "\" asked " + lacking + " for Vulkan " +
                                 what + " it does not offer (" + call + ": " + vk_result_name(vr) +
                                 "; update the GPU driver)",
                             XR_ERROR_RUNTIME_FAILURE);
  throw XrError(
      std::string(file) + ":" + std::to_string(line) + ": " + call + " failed with " + vk_result_name(vr),
      XR_ERROR_RUNTIME_FAILURE);
}

// XR_KHR_vulkan_enable: create(info) (vkCreateInstance or vkCreateDevice, which leaves its handle null on
// failure) with the runtime's extensions `needed` added to info's; on failure, throw_vulkan_create_failure
// with the extensions listed() returns.
template <class CreateInfo, class Create, class Listed>
void create_with_runtime_extensions(CreateInfo info, const std::vector<std::string>& needed, Create create,
                                    Listed listed, const char* call, const char* what, const char* lacking,
                                    const std::string& runtime_name) {
  const std::vector<const char*> own(info.ppEnabledExtensionNames,
                                     info.ppEnabledExtensionNames + info.enabledExtensionCount);
  std::vector<const char*> names = own;
  add_unique(names, needed);
  info.enabledExtensionCount = uint32_t(names.size());
  info.ppEnabledExtensionNames = names.data();
  const VkResult vr = create(info);
  if (vr != VK_SUCCESS)
    throw_vulkan_create_failure(vr, std::string(call) + " for the runtime's XR_KHR_vulkan_enable", __FILE__,
                                __LINE__, own, needed, listed(), what, lacking, runtime_name);
}

// The instance extensions the Vulkan loader lists: the driver's, implicit layers' and those of `layers`.
std::vector<VkExtensionProperties> listed_instance_extensions(const VkInstanceCreateInfo& info) {
  std::vector<VkExtensionProperties> listed;
  append_listed(listed, [](uint32_t* n, VkExtensionProperties* p) {
    return vkEnumerateInstanceExtensionProperties(nullptr, n, p);
  });
  for (uint32_t i = 0; i < info.enabledLayerCount; ++i)
    append_listed(listed, [&](uint32_t* n, VkExtensionProperties* p) {
      return vkEnumerateInstanceExtensionProperties(info.ppEnabledLayerNames[i], n, p);
    });
  return listed;
}

std::vector<VkExtensionProperties> listed_device_extensions(VkPhysicalDevice device) {
  std::vector<VkExtensionProperties> listed;
  append_listed(listed, [&](uint32_t* n, VkExtensionProperties* p) {
    return vkEnumerateDeviceExtensionProperties(device, nullptr, n, p);
  });
  return listed;
}

// A GPU's VkPhysicalDeviceIDProperties::deviceUUID (Vulkan 1.1).
std::array<uint8_t, VK_UUID_SIZE> device_uuid(VkPhysicalDevice device) {
  VkPhysicalDeviceIDProperties id{};
  id.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  properties.pNext = &id;
  vkGetPhysicalDeviceProperties2(device, &properties);
  std::array<uint8_t, VK_UUID_SIZE> uuid{};
  std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), uuid.begin());
  return uuid;
}

template <class Fn>
Fn instance_function(XrInstance instance, const char* name) {
  PFN_xrVoidFunction f = nullptr;
  check_xr(xrGetInstanceProcAddr(instance, name, &f), instance, name, __FILE__, __LINE__);
  return reinterpret_cast<Fn>(f);
}

// xrGetSystem for a head-mounted display, asked again every 100 ms while the headset is not connected
// (XR_ERROR_FORM_FACTOR_UNAVAILABLE, "temporarily unavailable") for up to wait_s seconds; returns the last
// result.
// give_up (may be empty): asked between polls; true ends the wait as if it had timed out.
XrResult get_hmd_system(XrInstance instance, XrSystemId& system, double wait_s,
                        const std::function<bool()>& give_up = {}) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(std::max(wait_s, 0.0)));
  XrSystemGetInfo info{XR_TYPE_SYSTEM_GET_INFO};
  info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  for (;;) {
    const XrResult r = xrGetSystem(instance, &info, &system);
    if (r != XR_ERROR_FORM_FACTOR_UNAVAILABLE || std::chrono::steady_clock::now() >= deadline) return r;
    if (give_up && give_up()) return r;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

}  // namespace

struct Session::Impl {
  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  VulkanDevice vk;
  XrSession session = XR_NULL_HANDLE;
  XrSpace stage = XR_NULL_HANDLE;
  bool stage_is_local = false;
  bool space_changed = false;  // a REFERENCE_SPACE_CHANGE_PENDING for the space in use, not yet taken
  detail::EyeHold eye_hold;    // the eyes of frames whose views have orientation only
  std::vector<Swapchain> eyes;
  std::vector<XrViewConfigurationView> view_configs;
  XrEnvironmentBlendMode blend_mode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false, exit = false, lost = false;
  bool instance_lost = false;  // the instance itself (not only the session): nothing can be recreated
  // XR_KHR_vulkan_enable2 (the runtime creates the Vulkan instance and device from our create infos), or,
  // where the runtime offers only XR_KHR_vulkan_enable, that one (we create them with the extensions it
  // names).
  bool vulkan_enable2 = true;
  std::string runtime_name, system_name;
  std::vector<std::string> enabled_extensions;
  SessionOptions options;  // as created (eye size): a recreated session uses them again

  // The OpenXR instance goes before the Vulkan device and instance (as hello_xr does): a runtime may keep
  // objects of its own on our device until its instance is destroyed (SteamVR's command buffers,
  // semaphores and memory: ValveSoftware/openvr#1649, #1715), and a device destroyed under them is
  // undefined behaviour.
  //
  // A runtime that never returns from its teardown (SteamVR on Linux, in xrDestroyInstance as the loader
  // unloads it: ValveSoftware/SteamVR-for-Linux#422, #567) would keep the process alive after the review
  // has written everything: after kTeardownWait the process ends without it, with the status the review
  // was ending with (1 while an exception unwinds through here, else 0), saying so.
  static constexpr std::chrono::seconds kTeardownWait{10};
  ~Impl() {
    const int status = std::uncaught_exceptions() > 0 ? 1 : 0;
    std::mutex mutex;
    std::condition_variable returned;
    bool done = false;
    std::optional<std::thread> watchdog;
    try {
      watchdog.emplace([&] {
        std::unique_lock lock(mutex);
        if (returned.wait_for(lock, kTeardownWait, [&] { return done; })) return;
        std::fprintf(
            stderr,
            "pushpull: the OpenXR runtime (%s) did not return from its teardown within %lld s; ending "
            "without it (the review's work was written before)\n",
            runtime_name.c_str(), static_cast<long long>(kTeardownWait.count()));
        std::fflush(nullptr);
        std::_Exit(status);
      });
    } catch (const std::system_error&) {  // no thread to spare: the teardown goes unwatched
    }
    {
      const RuntimeCallScope runtime;  // the runtime may release its work on our device here
      eyes.clear();
      if (stage != XR_NULL_HANDLE) xrDestroySpace(stage);
      if (session != XR_NULL_HANDLE) xrDestroySession(session);
      if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
    }
    {
      const std::lock_guard lock(mutex);
      done = true;
    }
    returned.notify_one();
    if (watchdog) watchdog->join();
    if (vk.device != VK_NULL_HANDLE) vkDestroyDevice(vk.device, nullptr);
    if (vk.instance != VK_NULL_HANDLE) vkDestroyInstance(vk.instance, nullptr);
  }

  void create_instance(const SessionOptions& options) {
    const std::vector<XrExtensionProperties> offered = offered_extensions();
    vulkan_enable2 = lists(offered, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) ||
                     !lists(offered, XR_KHR_VULKAN_ENABLE_EXTENSION_NAME);
    std::vector<const char*> extensions{vulkan_enable2 ? XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME
                                                       : XR_KHR_VULKAN_ENABLE_EXTENSION_NAME};
    for (const auto& e : options.extensions) extensions.push_back(e.c_str());
    // Interaction profiles beyond OpenXR 1.0's (input.hpp): optional, enabled where offered.
    for (const std::string& e : controller_profile_extensions())
      if (lists(offered, e.c_str()) &&
          std::find(options.extensions.begin(), options.extensions.end(), e) == options.extensions.end())
        extensions.push_back(e.c_str());
    XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
    std::snprintf(info.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s",
                  options.application_name.c_str());
    std::snprintf(info.applicationInfo.engineName, XR_MAX_ENGINE_NAME_SIZE, "pushpull");
    info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.enabledExtensionNames = extensions.data();
    if (const XrResult r = xrCreateInstance(&info, &instance); XR_FAILED(r)) {
      instance = XR_NULL_HANDLE;
      const std::string missing = missing_extensions(offered, extensions);
      const std::string why = r == XR_ERROR_EXTENSION_NOT_PRESENT
                                  ? "it does not offer " + missing
                                  : "xrCreateInstance failed with " + result_name(XR_NULL_HANDLE, r);
      // A runtime that was found but would not start (its own messages above say why, e.g. xr/sim's about
      // its input script) needs fixing, not finding.
      const bool found = r != XR_ERROR_RUNTIME_UNAVAILABLE && std::getenv("XR_RUNTIME_JSON") != nullptr;
      throw RuntimeUnavailable("no usable OpenXR runtime: looked for " + runtime_looked_for() + ", " + why +
                                   " (the loader's and runtime's messages above say more); " +
                                   (found ? std::string("fix what they name, or ") : std::string()) +
                                   kPointAtRuntime,
                               r);
    }
    enabled_extensions.assign(extensions.begin(), extensions.end());
    XrInstanceProperties properties{XR_TYPE_INSTANCE_PROPERTIES};
    CHECK(xrGetInstanceProperties(instance, &properties));
    runtime_name = properties.runtimeName;
    XrResult r = get_hmd_system(instance, system, 0.0);
    if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE && options.headset_wait_s > 0.0) {
      std::fprintf(stderr,
                   "pushpull: the OpenXR runtime \"%s\" has no headset yet; waiting up to %.0f s for it\n",
                   runtime_name.c_str(), options.headset_wait_s);
      r = get_hmd_system(instance, system, options.headset_wait_s);
    }
    if (XR_FAILED(r)) {
      char waited[96] = "";
      if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE)
        std::snprintf(waited, sizeof waited, " after %.0f s (pushpull review --headset-wait S waits longer)",
                      options.headset_wait_s);
      throw RuntimeUnavailable("no headset: the OpenXR runtime \"" + runtime_name + "\" (" +
                                   runtime_looked_for() +
                                   ") has no head-mounted display (xrGetSystem: " + result_name(instance, r) +
                                   waited + "); connect one, or " + kPointAtRuntime,
                               r);
    }
    XrSystemProperties system_properties{XR_TYPE_SYSTEM_PROPERTIES};
    CHECK(xrGetSystemProperties(instance, system, &system_properties));
    system_name = system_properties.systemName;
  }

  // The spec requires this call before every xrCreateSession (also the one after a lost session: SteamVR
  // refuses a session whose requirements were not asked for).
  // (XrGraphicsRequirementsVulkan2KHR is XrGraphicsRequirementsVulkanKHR, the structure type the same.)
  // Both bindings' functions have the same signature.
  XrGraphicsRequirementsVulkan2KHR graphics_requirements() {
    XrGraphicsRequirementsVulkan2KHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
    const char* name =
        vulkan_enable2 ? "xrGetVulkanGraphicsRequirements2KHR" : "xrGetVulkanGraphicsRequirementsKHR";
    check_xr(
        instance_function<PFN_xrGetVulkanGraphicsRequirements2KHR>(instance, name)(instance, system, &req),
        instance, name, __FILE__, __LINE__);
    return req;
  }

  // The GPU the runtime renders on (vk.instance created).
  VkPhysicalDevice runtime_physical_device() {
    VkPhysicalDevice device = VK_NULL_HANDLE;
    if (vulkan_enable2) {
      XrVulkanGraphicsDeviceGetInfoKHR gi{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
      gi.systemId = system;
      gi.vulkanInstance = vk.instance;
      const char* name = "xrGetVulkanGraphicsDevice2KHR";
      check_xr(instance_function<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, name)(instance, &gi, &device),
               instance, name, __FILE__, __LINE__);
    } else {
      const char* name = "xrGetVulkanGraphicsDeviceKHR";
      check_xr(instance_function<PFN_xrGetVulkanGraphicsDeviceKHR>(instance, name)(instance, system,
                                                                                   vk.instance, &device),
               instance, name, __FILE__, __LINE__);
    }
    return device;
  }

  // XR_KHR_vulkan_enable2: the runtime's `name` (xrCreateVulkanInstanceKHR / xrCreateVulkanDeviceKHR) runs
  // `vk_call` for xinfo into `handle`; a failed VkResult leaves it null and is told by
  // throw_vulkan_create_failure (pushpull's extensions `own` against listed(); the runtime's are unknown).
  template <class Pfn, class XrInfo, class Handle, class Listed>
  void create_through_runtime(const char* name, const char* vk_call, const XrInfo& xinfo, Handle& handle,
                              const std::vector<const char*>& own, Listed listed, const char* what,
                              const char* lacking) {
    VkResult vr = VK_ERROR_UNKNOWN;
    check_xr(instance_function<Pfn>(instance, name)(instance, &xinfo, &handle, &vr), instance, name, __FILE__,
             __LINE__);
    if (vr == VK_SUCCESS) return;
    handle = VK_NULL_HANDLE;
    throw_vulkan_create_failure(vr, std::string(vk_call) + " through " + name, __FILE__, __LINE__, own, {},
                                listed(), what, lacking, runtime_name);
  }

  // XR_KHR_vulkan_enable: vkCreateInstance with the runtime's instance extensions added to `vci`'s.
  void create_vk_instance_v1(const VkInstanceCreateInfo& vci) {
    create_with_runtime_extensions(
        vci,
        runtime_vulkan_extensions(instance, system,
                                  instance_function<PFN_xrGetVulkanInstanceExtensionsKHR>(
                                      instance, "xrGetVulkanInstanceExtensionsKHR"),
                                  "xrGetVulkanInstanceExtensionsKHR"),
        [&](const VkInstanceCreateInfo& info) {
          const VkResult r = vkCreateInstance(&info, nullptr, &vk.instance);
          if (r != VK_SUCCESS) vk.instance = VK_NULL_HANDLE;
          return r;
        },
        [&] { return listed_instance_extensions(vci); }, "vkCreateInstance", "instance extensions",
        "the Vulkan driver", runtime_name);
  }

  // XR_KHR_vulkan_enable: vkCreateDevice with the runtime's device extensions added to `dci`'s.
  void create_vk_device_v1(const VkDeviceCreateInfo& dci) {
    create_with_runtime_extensions(
        dci,
        runtime_vulkan_extensions(
            instance, system,
            instance_function<PFN_xrGetVulkanDeviceExtensionsKHR>(instance, "xrGetVulkanDeviceExtensionsKHR"),
            "xrGetVulkanDeviceExtensionsKHR"),
        [&](const VkDeviceCreateInfo& info) {
          const VkResult r = vkCreateDevice(vk.physical_device, &info, nullptr, &vk.device);
          if (r != VK_SUCCESS) vk.device = VK_NULL_HANDLE;
          return r;
        },
        [&] { return listed_device_extensions(vk.physical_device); }, "vkCreateDevice", "device extensions",
        "the runtime's GPU", runtime_name);
  }

  void create_vulkan(const SessionOptions& options) {
    const XrGraphicsRequirementsVulkan2KHR req = graphics_requirements();
    if (!vulkan_enable2)
      std::fprintf(
          stderr,
          "pushpull: note: the OpenXR runtime \"%s\" offers XR_KHR_vulkan_enable, not enable2: pushpull "
          "creates the Vulkan instance and device itself, with the extensions the runtime names\n",
          runtime_name.c_str());
    if (XR_VERSION_MAJOR(req.maxApiVersionSupported) < 1 ||
        (XR_VERSION_MAJOR(req.maxApiVersionSupported) == 1 &&
         XR_VERSION_MINOR(req.maxApiVersionSupported) < 3))
      // maxApiVersionSupported is the newest version the runtime was tested with (SteamVR says 1.2), not a
      // limit: the device the runtime picks decides (checked below).
      std::fprintf(
          stderr,
          "pushpull: note: the OpenXR runtime was tested with Vulkan up to %u.%u; pushpull uses 1.3 and "
          "goes on if the runtime's GPU offers it\n",
          unsigned(XR_VERSION_MAJOR(req.maxApiVersionSupported)),
          unsigned(XR_VERSION_MINOR(req.maxApiVersionSupported)));

    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = options.application_name.c_str();
    app.pEngineName = "pushpull";
    app.apiVersion = VK_API_VERSION_1_3;
    // A runtime that supports only newer instance versions gets its minimum: pushpull's 1.3 calls work on a
    // newer instance (apiVersion is the newest version the application uses, the GPU decides below).
    const uint32_t min_major = uint32_t(XR_VERSION_MAJOR(req.minApiVersionSupported));
    const uint32_t min_minor = uint32_t(XR_VERSION_MINOR(req.minApiVersionSupported));
    // (Vulkan packs major in 7 bits and minor in 10: a value beyond them is malformed and left alone.)
    if ((min_major > 1 || (min_major == 1 && min_minor > 3)) && min_major < 128 && min_minor < 1024 &&
        req.minApiVersionSupported <= req.maxApiVersionSupported) {
      std::fprintf(stderr,
                   "pushpull: note: the OpenXR runtime supports Vulkan %u.%u and newer; pushpull's Vulkan "
                   "instance asks for %u.%u (it uses 1.3)\n",
                   unsigned(min_major), unsigned(min_minor), unsigned(min_major), unsigned(min_minor));
      app.apiVersion = VK_MAKE_API_VERSION(0, min_major, min_minor, 0);
    }
    VkInstanceCreateInfo vci{};
    vci.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    vci.pApplicationInfo = &app;
    std::vector<const char*> instance_extensions;
    for (const auto& e : options.vulkan_instance_extensions) instance_extensions.push_back(e.c_str());
    vci.enabledExtensionCount = uint32_t(instance_extensions.size());
    vci.ppEnabledExtensionNames = instance_extensions.data();
    std::vector<const char*> layers;
    for (const auto& l : options.vulkan_layers) layers.push_back(l.c_str());
    vci.enabledLayerCount = uint32_t(layers.size());
    vci.ppEnabledLayerNames = layers.data();
    if (vulkan_enable2) {
      XrVulkanInstanceCreateInfoKHR xci{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
      xci.systemId = system;
      xci.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
      xci.vulkanCreateInfo = &vci;
      create_through_runtime<PFN_xrCreateVulkanInstanceKHR>(
          "xrCreateVulkanInstanceKHR", "vkCreateInstance", xci, vk.instance, instance_extensions,
          [&] { return listed_instance_extensions(vci); }, "instance extensions", "the Vulkan driver");
    } else {
      create_vk_instance_v1(vci);
    }
    vk.physical_device = runtime_physical_device();
    {  // A GPU without Vulkan 1.3 cannot run the renderer: say so, and the review opens the desktop window.
      VkPhysicalDeviceProperties gpu{};
      vkGetPhysicalDeviceProperties(vk.physical_device, &gpu);
      if (VK_API_VERSION_MAJOR(gpu.apiVersion) == 1 && VK_API_VERSION_MINOR(gpu.apiVersion) < 3)
        throw RuntimeUnavailable("the OpenXR runtime \"" + runtime_name + "\" renders on " + gpu.deviceName +
                                     ", which offers Vulkan " +
                                     std::to_string(VK_API_VERSION_MAJOR(gpu.apiVersion)) + "." +
                                     std::to_string(VK_API_VERSION_MINOR(gpu.apiVersion)) +
                                     "; pushpull needs 1.3 (update the GPU driver)",
                                 XR_ERROR_RUNTIME_FAILURE);
    }

    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(vk.physical_device, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(vk.physical_device, &n, families.data());
    std::optional<uint32_t> family;
    for (uint32_t i = 0; i < n && !family; ++i)
      if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) family = i;
    if (!family) throw XrError("the runtime's Vulkan device has no graphics queue", XR_ERROR_RUNTIME_FAILURE);
    vk.queue_family_index = *family;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{};
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = vk.queue_family_index;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan13Features features13{};
    features13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
    if (options.require_vulkan13_features) options.require_vulkan13_features(features13);
    VkDeviceCreateInfo dci{};
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.pNext = &features13;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    std::vector<const char*> device_extensions;
    for (const auto& e : options.vulkan_device_extensions) device_extensions.push_back(e.c_str());
    dci.enabledExtensionCount = uint32_t(device_extensions.size());
    dci.ppEnabledExtensionNames = device_extensions.data();
    if (vulkan_enable2) {
      XrVulkanDeviceCreateInfoKHR xdci{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
      xdci.systemId = system;
      xdci.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
      xdci.vulkanPhysicalDevice = vk.physical_device;
      xdci.vulkanCreateInfo = &dci;
      create_through_runtime<PFN_xrCreateVulkanDeviceKHR>(
          "xrCreateVulkanDeviceKHR", "vkCreateDevice", xdci, vk.device, device_extensions,
          [&] { return listed_device_extensions(vk.physical_device); }, "device extensions",
          "the runtime's GPU");
    } else {
      // XR_KHR_vulkan_enable leaves no way for the runtime to add feature structures to the device it
      // composites with, and its compositors wait on timeline semaphores (core since Vulkan 1.2, which
      // this device has): enabled here. (Not on the enable2 path: runtimes add their own structure there,
      // and two of a kind in one chain are invalid.)
      VkPhysicalDeviceTimelineSemaphoreFeatures timeline{};
      timeline.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES;
      timeline.timelineSemaphore = VK_TRUE;
      features13.pNext = &timeline;
      create_vk_device_v1(dci);
      features13.pNext = nullptr;
    }
    vkGetDeviceQueue(vk.device, vk.queue_family_index, 0, &vk.queue);
  }

  void create_session() {
    XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
    binding.instance = vk.instance;
    binding.physicalDevice = vk.physical_device;
    binding.device = vk.device;
    binding.queueFamilyIndex = vk.queue_family_index;
    binding.queueIndex = 0;
    XrSessionCreateInfo info{XR_TYPE_SESSION_CREATE_INFO};
    info.next = &binding;
    info.systemId = system;
    CHECK(xrCreateSession(instance, &info, &session));
  }

  void create_stage_space() {
    // A recreated session (after a loss) may find STAGE where the first had none (a boundary set since), and
    // a change pending for the old space is not one for the new.
    stage_is_local = false;
    space_changed = false;
    eye_hold = {};  // its head centre was in the old space's coordinates
    uint32_t n = 0;
    CHECK(xrEnumerateReferenceSpaces(session, 0, &n, nullptr));
    std::vector<XrReferenceSpaceType> types(n);
    CHECK(xrEnumerateReferenceSpaces(session, n, &n, types.data()));
    XrReferenceSpaceCreateInfo info{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
    info.poseInReferenceSpace.orientation.w = 1.0f;
    if (std::find(types.begin(), types.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != types.end()) {
      info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_STAGE;
    } else {
      // LOCAL has its origin at the head when the app started: put the floor 1.6 m below it (a guess).
      info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
      info.poseInReferenceSpace.position.y = -1.6f;
      stage_is_local = true;
      std::fprintf(stderr,
                   "pushpull: the OpenXR runtime has no STAGE space; using LOCAL with the floor guessed "
                   "1.6 m below the head\n");
    }
    CHECK(xrCreateReferenceSpace(session, &info, &stage));
  }

  void create_swapchains(const SessionOptions& options) {
    uint32_t n = 0;
    const XrResult stereo = xrEnumerateViewConfigurationViews(
        instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &n, nullptr);
    if (stereo == XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED || (XR_SUCCEEDED(stereo) && n != 2))
      throw RuntimeUnavailable("the OpenXR runtime \"" + runtime_name + "\" has no stereo headset view (" +
                                   (XR_SUCCEEDED(stereo) ? std::to_string(n) + " views in PRIMARY_STEREO"
                                                         : "no PRIMARY_STEREO view configuration") +
                                   ")",
                               XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
    check_xr(stereo, instance, "xrEnumerateViewConfigurationViews(PRIMARY_STEREO)", __FILE__, __LINE__);
    view_configs.assign(n, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
    CHECK(xrEnumerateViewConfigurationViews(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, n,
                                            &n, view_configs.data()));
    uint32_t format_count = 0;
    CHECK(xrEnumerateSwapchainFormats(session, 0, &format_count, nullptr));
    std::vector<int64_t> formats(format_count);
    CHECK(xrEnumerateSwapchainFormats(session, format_count, &format_count, formats.data()));
    // The runtime lists its formats best first: the first sRGB 8-bit colour format of the list (the renderer
    // writes linear colour and lets the format encode it).
    int64_t format = 0;
    for (const int64_t offered : formats)
      if (format == 0 &&
          (offered == int64_t(VK_FORMAT_R8G8B8A8_SRGB) || offered == int64_t(VK_FORMAT_B8G8R8A8_SRGB)))
        format = offered;
    if (format == 0)
      throw RuntimeUnavailable(
          "the OpenXR runtime \"" + runtime_name +
              "\" offers no sRGB colour swapchain format (R8G8B8A8_SRGB or B8G8R8A8_SRGB)",
          XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
    // One size for both eyes (the renderer draws both into one set of attachments): the larger recommended
    // size, within both eyes' maxima.
    uint32_t w = 0, h = 0, max_w = UINT32_MAX, max_h = UINT32_MAX;
    for (const auto& view : view_configs) {
      w = std::max(w, view.recommendedImageRectWidth);
      h = std::max(h, view.recommendedImageRectHeight);
      max_w = std::min(max_w, view.maxImageRectWidth);
      max_h = std::min(max_h, view.maxImageRectHeight);
    }
    if (options.eye_width) w = options.eye_width;
    if (options.eye_height) h = options.eye_height;
    w = std::max(1u, std::min(w, max_w));
    h = std::max(1u, std::min(h, max_h));
    for (size_t eye = 0; eye < view_configs.size(); ++eye)
      eyes.emplace_back(instance, session, format, w, h, options.eye_transfer_source);
    uint32_t blend_count = 0;
    CHECK(xrEnumerateEnvironmentBlendModes(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0,
                                           &blend_count, nullptr));
    std::vector<XrEnvironmentBlendMode> modes(blend_count);
    CHECK(xrEnumerateEnvironmentBlendModes(instance, system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO,
                                           blend_count, &blend_count, modes.data()));
    if (!modes.empty() &&
        std::find(modes.begin(), modes.end(), XR_ENVIRONMENT_BLEND_MODE_OPAQUE) == modes.end())
      blend_mode = modes.front();
  }

  // true: the call succeeded; false: the session is lost (recorded). Other failures throw.
  bool ok_unless_lost(XrResult r, const char* expression, int line) {
    if (r == XR_ERROR_SESSION_LOST || r == XR_ERROR_INSTANCE_LOST) {
      lost = exit = true;
      instance_lost = instance_lost || r == XR_ERROR_INSTANCE_LOST;
      running = false;
      return false;
    }
    check_xr(r, instance, expression, __FILE__, line);
    return true;
  }
};

#define CHECK_UNLESS_LOST(expression) \
  impl_->ok_unless_lost((::pushpull::xr::RuntimeCallScope{}, (expression)), #expression, __LINE__)

Session::Session(const SessionOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->create_instance(options);
  impl_->create_vulkan(options);
  impl_->create_session();
  impl_->create_stage_space();
  impl_->create_swapchains(options);
}

Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

void Session::poll_events() {
  Impl& s = *impl_;
  const XrInstance instance = s.instance;
  for (;;) {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult r = xrPollEvent(instance, &event);
    if (r == XR_EVENT_UNAVAILABLE) return;
    if (!CHECK_UNLESS_LOST(r)) return;
    switch (event.type) {
      case XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING:
        s.lost = s.exit = s.instance_lost = true;
        break;
      case XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED: {
        const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        if (changed.session != s.session) break;  // a session lost and destroyed before recreate_after_loss
        s.state = changed.state;
        switch (changed.state) {
          case XR_SESSION_STATE_READY: {
            XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
            begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
            if (CHECK_UNLESS_LOST(xrBeginSession(s.session, &begin))) s.running = true;
            break;
          }
          case XR_SESSION_STATE_STOPPING:
            s.running = false;
            CHECK_UNLESS_LOST(xrEndSession(s.session));
            break;
          case XR_SESSION_STATE_EXITING:
            s.exit = true;
            break;
          case XR_SESSION_STATE_LOSS_PENDING:
            s.running = false;
            s.lost = s.exit = true;
            break;
          default:
            break;
        }
        break;
      }
      case XR_TYPE_EVENT_DATA_REFERENCE_SPACE_CHANGE_PENDING: {
        const auto& change = reinterpret_cast<const XrEventDataReferenceSpaceChangePending&>(event);
        const XrReferenceSpaceType used =
            s.stage_is_local ? XR_REFERENCE_SPACE_TYPE_LOCAL : XR_REFERENCE_SPACE_TYPE_STAGE;
        if (change.session == s.session && change.referenceSpaceType == used) s.space_changed = true;
        break;
      }
      case XR_TYPE_EVENT_DATA_EVENTS_LOST: {
        // The runtime's queue overflowed: a state change may be among the dropped events, and core OpenXR
        // has no call to ask for the state again. Said, so that a review stuck waiting is explained.
        const auto& dropped = reinterpret_cast<const XrEventDataEventsLost&>(event);
        std::fprintf(
            stderr,
            "pushpull review: the OpenXR runtime dropped %u event(s) (its event queue overflowed); a "
            "session state change may have been missed\n",
            dropped.lostEventCount);
        break;
      }
      default:
        break;  // interaction profile changes: Input queries them
    }
  }
}

bool Session::take_space_change() {
  const bool changed = impl_->space_changed;
  impl_->space_changed = false;
  return changed;
}

XrEnvironmentBlendMode Session::blend_mode() const {
  return impl_->blend_mode;
}

bool Session::running() const {
  return impl_->running && !impl_->lost;
}
bool Session::focused() const {
  return impl_->state == XR_SESSION_STATE_FOCUSED;
}
bool Session::exit_requested() const {
  return impl_->exit;
}
bool Session::lost() const {
  return impl_->lost;
}
XrSessionState Session::state() const {
  return impl_->state;
}

void Session::request_exit() {
  if (impl_->running) {
    CHECK_UNLESS_LOST(xrRequestExitSession(impl_->session));
  } else {
    impl_->exit = true;
  }
}

FrameViews Session::begin_frame() {
  Impl& s = *impl_;
  FrameViews frame;
  XrFrameState state{XR_TYPE_FRAME_STATE};
  XrFrameWaitInfo wait{XR_TYPE_FRAME_WAIT_INFO};
  if (!CHECK_UNLESS_LOST(xrWaitFrame(s.session, &wait, &state))) return frame;
  XrFrameBeginInfo begin{XR_TYPE_FRAME_BEGIN_INFO};
  if (!CHECK_UNLESS_LOST(xrBeginFrame(s.session, &begin))) return frame;
  frame.predicted_display_time = state.predictedDisplayTime;
  frame.predicted_display_period = state.predictedDisplayPeriod;
  if (!state.shouldRender) return frame;
  XrViewLocateInfo locate{XR_TYPE_VIEW_LOCATE_INFO};
  locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  locate.displayTime = state.predictedDisplayTime;
  locate.space = s.stage;
  XrViewState view_state{XR_TYPE_VIEW_STATE};
  std::array<XrView, 2> views{{{XR_TYPE_VIEW}, {XR_TYPE_VIEW}}};
  uint32_t n = 0;
  if (!CHECK_UNLESS_LOST(xrLocateViews(s.session, &locate, &view_state, 2, &n, views.data()))) return frame;
  if (n != 2 || (view_state.viewStateFlags & XR_VIEW_STATE_ORIENTATION_VALID_BIT) == 0) return frame;
  // Orientation without position (rotation-only tracking, or positional tracking lost): the head stays where
  // it was last located (else at a standing reviewer's height) and the eyes turn about it with their live
  // orientations, rather than the view going black (eyes held in place would lose stereo as the head turns).
  bool position = (view_state.viewStateFlags & XR_VIEW_STATE_POSITION_VALID_BIT) != 0;
  // Numbers that are not finite: a view without a usable orientation or field of view is not drawn (the
  // frame ends without layers, as without orientation); a position that is not finite counts as not valid.
  for (const XrView& view : views) {
    if (!detail::finite_fov(view.fov) || !detail::finite_orientation(view.pose.orientation)) return frame;
    if (!detail::finite_position(view.pose.position)) position = false;
  }
  std::array<XrPosef, 2> poses{views[0].pose, views[1].pose};
  s.eye_hold.apply(poses, position);
  for (size_t i = 0; i < 2; ++i) frame.eyes[i] = {poses[i], views[i].fov};
  frame.should_render = true;
  frame.position_valid = position;
  return frame;
}

void Session::end_frame(const FrameViews& frame, bool rendered) {
  Impl& s = *impl_;
  for (auto& eye : s.eyes) eye.release();
  if (s.lost) return;
  std::array<XrCompositionLayerProjectionView, 2> views{};
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<XrCompositionLayerBaseHeader*>(&layer)};
  XrFrameEndInfo end{XR_TYPE_FRAME_END_INFO};
  end.displayTime = frame.predicted_display_time;
  end.environmentBlendMode = s.blend_mode;
  if (rendered && frame.should_render) {
    for (size_t i = 0; i < 2; ++i) {
      views[i] = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW};
      views[i].pose = frame.eyes[i].T_stage_eye;
      views[i].fov = frame.eyes[i].fov;
      views[i].subImage.swapchain = s.eyes[i].handle();
      views[i].subImage.imageRect.extent = {int32_t(s.eyes[i].width()), int32_t(s.eyes[i].height())};
      views[i].subImage.imageArrayIndex = 0;
    }
    layer.space = s.stage;
    // See-through blending by alpha: the eyes' cleared background (alpha 0) lets the world through.
    if (s.blend_mode == XR_ENVIRONMENT_BLEND_MODE_ALPHA_BLEND)
      layer.layerFlags = XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT;
    layer.viewCount = 2;
    layer.views = views.data();
    end.layerCount = 1;
    end.layers = layers;
  }
  CHECK_UNLESS_LOST(xrEndFrame(s.session, &end));
}

bool Session::recreate_after_loss(double timeout_s, const std::function<bool()>& give_up) {
  Impl& s = *impl_;
  if (s.instance_lost) return false;
  // The lost session's handles go first (the spec: destroy it, then poll xrGetSystem until the headset is
  // back).
  s.eyes.clear();
  const RuntimeCallScope runtime;
  if (s.stage != XR_NULL_HANDLE) xrDestroySpace(s.stage);
  if (s.session != XR_NULL_HANDLE) xrDestroySession(s.session);
  s.stage = XR_NULL_HANDLE;
  s.session = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  const XrResult r = get_hmd_system(s.instance, system, timeout_s, give_up);
  if (r == XR_ERROR_INSTANCE_LOST) {
    s.instance_lost = true;
    return false;
  }
  if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE) return false;  // not back in time
  if (XR_FAILED(r)) check_xr(r, s.instance, "xrGetSystem", __FILE__, __LINE__);
  if (system != s.system)
    throw XrError("the headset came back as another system (" + std::to_string(system) + ", was " +
                      std::to_string(s.system) + "): the Vulkan device belongs to the old one; start again",
                  XR_ERROR_SYSTEM_INVALID);
  (void)s.graphics_requirements();
  // The GPU the runtime names now must still be the one pushpull's device was made on. Compared by its UUID:
  // Vulkan does not promise the same VkPhysicalDevice handle on every enumeration (older loaders rebuilt
  // them).
  if (device_uuid(s.runtime_physical_device()) != device_uuid(s.vk.physical_device))
    throw XrError("the OpenXR runtime \"" + s.runtime_name +
                      "\" renders on another GPU since the session was lost: the Vulkan device belongs to "
                      "the old one; start again",
                  XR_ERROR_GRAPHICS_DEVICE_INVALID);
  s.create_session();
  s.create_stage_space();
  s.create_swapchains(s.options);
  s.lost = s.exit = s.running = false;
  s.state = XR_SESSION_STATE_IDLE;
  return true;
}

Swapchain& Session::eye(int index) {
  return impl_->eyes.at(size_t(index));
}
const VulkanDevice& Session::vulkan() const {
  return impl_->vk;
}
XrInstance Session::instance() const {
  return impl_->instance;
}
XrSession Session::handle() const {
  return impl_->session;
}
XrSpace Session::stage_space() const {
  return impl_->stage;
}
bool Session::stage_is_local() const {
  return impl_->stage_is_local;
}
const std::string& Session::runtime_name() const {
  return impl_->runtime_name;
}
const std::vector<std::string>& Session::enabled_extensions() const {
  return impl_->enabled_extensions;
}
const std::string& Session::system_name() const {
  return impl_->system_name;
}

}  // namespace pushpull::xr
