#include "state.hpp"

#include <set>
#include <sstream>

#include "dispatch.hpp"

#include <cstdlib>
#include <cstring>
#include <ctime>

namespace pushpull::xrsim {
namespace {

std::unordered_map<const void*, HandleKind>& handles() {
  static std::unordered_map<const void*, HandleKind> map;
  return map;
}

uint32_t env_uint(const char* name, uint32_t fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == 0) return fallback;
  char* end = nullptr;
  const unsigned long n = std::strtoul(v, &end, 10);
  return (end != v && n > 0 && n < 1u << 16) ? static_cast<uint32_t>(n) : fallback;
}

std::string env_string(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::string(v) : std::string();
}

}  // namespace

Config Config::from_env() {
  Config c;
  c.width = env_uint("PUSHPULL_XR_SIM_WIDTH", c.width);
  c.height = env_uint("PUSHPULL_XR_SIM_HEIGHT", c.height);
  c.rate_hz = env_uint("PUSHPULL_XR_SIM_RATE", 90);
  c.input_script = env_string("PUSHPULL_XR_SIM_INPUT");
  c.capture_dir = env_string("PUSHPULL_XR_SIM_CAPTURE");
  c.capture_every = env_uint("PUSHPULL_XR_SIM_CAPTURE_EVERY", 0);
  c.profile = env_string("PUSHPULL_XR_SIM_PROFILE");
  c.vk_device = env_string("PUSHPULL_XR_SIM_VK_DEVICE");
  c.haptics_log = env_string("PUSHPULL_XR_SIM_HAPTICS");
  c.pace = env_uint("PUSHPULL_XR_SIM_PACE", 0) != 0;
  c.headset_after_ms = env_uint("PUSHPULL_XR_SIM_HEADSET_AFTER_MS", 0);
  c.rotation_only = env_uint("PUSHPULL_XR_SIM_ROTATION_ONLY", 0) != 0;
  c.stage_height_m = float(env_uint("PUSHPULL_XR_SIM_STAGE_MM", 0)) * 1e-3f;
  if (env_string("PUSHPULL_XR_SIM_BLEND") == "additive") c.blend_mode = XR_ENVIRONMENT_BLEND_MODE_ADDITIVE;
  std::set<std::string> quirks;
  {
    std::stringstream list(env_string("PUSHPULL_XR_SIM_QUIRKS"));
    for (std::string item; std::getline(list, item, ',');) quirks.insert(item);
  }
  auto quirk = [&](const char* name) { return quirks.count(name) > 0; };
  c.refuse_transfer_source = quirk("no-transfer-src");
  c.refuse_transfer_source_as_format = quirk("no-transfer-src-format");
  c.validation_noise = quirk("validation-noise");
  if (const std::string name = env_string("PUSHPULL_XR_SIM_RUNTIME_NAME"); !name.empty())
    c.runtime_name = name;
  c.unorm_first = quirk("unorm-first");
  c.eyes_differ = quirk("eyes-differ");
  c.requirements_per_session = quirk("requirements-per-session");
  c.haptics_fail = quirk("haptics-fail");
  c.position_late = quirk("position-late");
  c.stays_lost = quirk("stays-lost");
  c.ignores_exit = quirk("ignores-exit");
  c.wait_timeout = quirk("wait-timeout");
  c.canted = quirk("canted");
  c.hangs_on_destroy = quirk("hangs-on-destroy");
  c.vulkan1_only = quirk("vulkan1-only");
  c.no_vulkan = quirk("no-vulkan");
  c.no_controller_extensions = quirk("no-controller-extensions");
  c.unknown_vk_extension = quirk("unknown-vk-extension");
  c.unknown_vk_device_extension = quirk("unknown-vk-device-extension");
  return c;
}

std::recursive_mutex& big_lock() {
  static std::recursive_mutex mutex;
  return mutex;
}

void register_handle(const void* object, HandleKind kind) {
  handles()[object] = kind;
}
void unregister_handle(const void* object) {
  handles().erase(object);
}
bool handle_is(const void* object, HandleKind kind) {
  const auto it = handles().find(object);
  return it != handles().end() && it->second == kind;
}

XrTime monotonic_now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<XrTime>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

XrPath Instance::intern(const std::string& path) {
  const auto it = path_ids.find(path);
  if (it != path_ids.end()) return it->second;
  path_strings.push_back(path);
  const XrPath id = path_strings.size();
  path_ids.emplace(path, id);
  return id;
}

const std::string* Instance::path_string(XrPath path) const {
  if (path == XR_NULL_PATH || path > path_strings.size()) return nullptr;
  return &path_strings[path - 1];
}

void Instance::push_event(const XrEventDataBuffer& event) {
  events.push_back(event);
}

XrTime Session::input_time() const {
  if (!is_virtual_clock()) return monotonic_now();
  return last_display_time != 0 ? last_display_time : clock_origin;
}

void Session::set_state(XrSessionState next, XrTime time) {
  state = next;
  XrEventDataBuffer buffer{};
  auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e->session = to_handle<XrSession>(this);
  e->state = next;
  e->time = time;
  instance->push_event(buffer);
}

XrResult two_call_string(const std::string& s, uint32_t capacity, uint32_t* count_output, char* buffer) {
  if (count_output == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  const uint32_t n = static_cast<uint32_t>(s.size() + 1);
  *count_output = n;
  if (capacity == 0) return XR_SUCCESS;
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
  std::memcpy(buffer, s.c_str(), n);
  return XR_SUCCESS;
}

}  // namespace pushpull::xrsim
