// Objects behind the simulated runtime's OpenXR handles and the locking that guards them.
//
// Threading: every entry point takes big_lock() (a recursive mutex) for its whole body, so the
// runtime is safe to call from several threads as OpenXR requires; xrWaitFrame releases it while
// it paces or waits for xrBeginFrame (so xrBeginFrame/xrEndFrame may run on another thread).
// Handles are the addresses of these objects; lookup<T>() checks that a handle is live and of the
// right type (XR_ERROR_HANDLE_INVALID otherwise). Times are XrTime nanoseconds on CLOCK_MONOTONIC;
// poses are T_stage_x (STAGE space, meters).
#pragma once

#include "input_script.hpp"
#include "profiles.hpp"

#define XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_TIMESPEC
// Vulkan first: openxr_platform.h uses its types.
#include <vulkan/vulkan.h>

#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace pushpull::xrsim {

constexpr XrSystemId kSystemId = 1;

// Runtime configuration from the environment (read at xrCreateInstance):
//   PUSHPULL_XR_SIM_WIDTH / _HEIGHT   recommended per-eye image size (default 1440 x 1600)
//   PUSHPULL_XR_SIM_RATE              display refresh rate in Hz (default 90)
//   PUSHPULL_XR_SIM_INPUT             JSON Lines input script (virtual clock when set)
//   PUSHPULL_XR_SIM_CAPTURE           folder for captured eye images (PNG)
//   PUSHPULL_XR_SIM_CAPTURE_EVERY     also capture every N frames (default 0: only at "capture" events)
//   PUSHPULL_XR_SIM_PROFILE           interaction profile to make current (default: first suggested of
//                                     khr/simple, oculus/touch, valve/index, htc/vive, microsoft/motion;
//                                     "none": no controller is on, nothing is bound)
//   PUSHPULL_XR_SIM_PACE              1: with an input script, xrWaitFrame still waits for the frame's
//                                     moment on the real clock (a headset's pacing: the app idles between
//                                     frames; for frame-time benchmarks); default 0: returns at once
//   PUSHPULL_XR_SIM_VK_DEVICE         substring of the Vulkan device name to use (default: a GPU, else
//                                     lavapipe)
//   PUSHPULL_XR_SIM_HAPTICS           JSON Lines file each haptic output is appended to
//                                     ({"t": s, "path": ..., "duration_ns": .., "frequency": .., "amplitude":
//                                     ..} or {"t": s, "path": ..., "stop": true}; t in script seconds)
//   PUSHPULL_XR_SIM_HEADSET_AFTER_MS  the headset connects N ms after xrCreateInstance (xrGetSystem says
//                                     XR_ERROR_FORM_FACTOR_UNAVAILABLE before; default 0)
//   PUSHPULL_XR_SIM_BLEND             additive: a see-through display (only ADDITIVE blending; default
//                                     OPAQUE)
//   PUSHPULL_XR_SIM_ROTATION_ONLY     1: views carry orientation, not position (a 3-DoF headset)
//   PUSHPULL_XR_SIM_RUNTIME_NAME      the runtime's name in xrGetInstanceProperties (default "pushpull
//                                     simulated runtime"), to pose as another runtime
//   PUSHPULL_XR_SIM_STAGE_MM          the STAGE space's origin N mm above the floor the script's poses stand
//                                     on (a runtime whose STAGE is its tracking origin, not the floor; 0)
//   PUSHPULL_XR_SIM_QUIRKS            comma-separated behaviours of other runtimes that the spec allows:
//                                     no-transfer-src (xrCreateSwapchain refuses TRANSFER_SRC usage with
//                                     XR_ERROR_FEATURE_UNSUPPORTED), no-transfer-src-format (the same
//                                     with XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED, the wrong code, as a
//                                     runtime that checks the format and usage pair might),
//                                     validation-noise (the first xrEndFrame creates a zero-sized buffer on
//                                     the application's device, as a runtime's own Vulkan mistakes would),
//                                     unorm-first
//                                     (UNORM formats listed before sRGB ones, B8G8R8A8 before R8G8B8A8),
//                                     eyes-differ (the right eye's recommended size is 16 px wider and 8 px
//                                     taller), requirements-per-session (xrCreateSession needs
//                                     xrGetVulkanGraphicsRequirements2KHR since the last session, as
//                                     SteamVR), haptics-fail (xrApplyHapticFeedback says
//                                     XR_ERROR_RUNTIME_FAILURE), position-late (the views' positions are
//                                     not valid for the first 10 frames, their orientation is: tracking
//                                     that finds the room after start-up), stays-lost (after a scripted
//                                     "loss" the headset never comes back: xrGetSystem says
//                                     XR_ERROR_FORM_FACTOR_UNAVAILABLE), ignores-exit
//                                     (xrRequestExitSession succeeds but the session goes on), wait-timeout
//                                     (the first xrWaitSwapchainImage of each acquired image returns
//                                     XR_TIMEOUT_EXPIRED, a success code, though the wait was infinite),
//                                     canted (each eye's view turned outwards by 10 deg about the head's
//                                     +Y, its field of view turned back: a display with canted panels),
//                                     hangs-on-destroy (xrDestroyInstance never returns, as SteamVR's on
//                                     Linux may not),
//                                     vulkan1-only (XR_KHR_vulkan_enable2 is neither listed nor accepted:
//                                     a runtime with only the first Vulkan binding, which names Vulkan
//                                     extensions the application must enable, and refuses a session whose
//                                     instance or device lacks them; with unknown-vk-extension also an
//                                     instance extension no Vulkan driver has, with
//                                     unknown-vk-device-extension a device extension), no-vulkan (neither
//                                     XR_KHR_vulkan_enable2 nor XR_KHR_vulkan_enable: a runtime for other
//                                     graphics APIs), no-controller-extensions (none of the extensions that
//                                     bring interaction profiles: XR_EXT_hp_mixed_reality_controller,
//                                     XR_HTC_vive_cosmos_controller_interaction,
//                                     XR_EXT_samsung_odyssey_controller)
struct Config {
  uint32_t width = 1440;
  uint32_t height = 1600;
  double rate_hz = 90.0;
  std::string input_script;
  std::string capture_dir;
  uint32_t capture_every = 0;
  std::string profile;
  std::string vk_device;
  std::string haptics_log;
  bool pace = false;  // scripted: also wait for each frame's moment on the real clock
  float ipd_m = 0.064f;
  // The headset connects this many milliseconds (real clock) after the instance is created; before,
  // xrGetSystem says XR_ERROR_FORM_FACTOR_UNAVAILABLE, as a streaming runtime does before its headset
  // connects.
  uint32_t headset_after_ms = 0;
  // The one environment blend mode the display offers: OPAQUE (a headset), or ADDITIVE (see-through).
  XrEnvironmentBlendMode blend_mode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  bool rotation_only = false;  // views report orientation, not position (a 3-DoF headset)
  float stage_height_m = 0.f;  // the STAGE origin's height above the scripts' floor
  // PUSHPULL_XR_SIM_QUIRKS (see above).
  bool refuse_transfer_source = false;
  bool refuse_transfer_source_as_format = false;  // with XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED
  bool validation_noise = false;  // the first xrEndFrame makes a Vulkan call the validation layer flags
  std::string runtime_name = "pushpull simulated runtime";  // PUSHPULL_XR_SIM_RUNTIME_NAME
  bool unorm_first = false;
  bool eyes_differ = false;
  bool requirements_per_session = false;
  bool haptics_fail = false;
  bool position_late = false;
  bool stays_lost = false;
  bool ignores_exit = false;
  bool wait_timeout = false;
  bool canted = false;
  bool hangs_on_destroy = false;  // xrDestroyInstance never returns  // each eye's view turned outwards by 10
                                  // deg (its field of view turned back)  // the first xrWaitSwapchainImage of
                                  // each acquired image: XR_TIMEOUT_EXPIRED
  bool vulkan1_only = false;
  bool no_vulkan = false;
  bool no_controller_extensions = false;     // offers none of the controller-profile extensions
  bool unknown_vk_extension = false;         // an instance extension no driver has (XR_KHR_vulkan_enable)
  bool unknown_vk_device_extension = false;  // a device extension no driver has (XR_KHR_vulkan_enable)
  static Config from_env();
};

enum class HandleKind { instance, session, space, action_set, action, swapchain };

std::recursive_mutex& big_lock();
using Lock = std::unique_lock<std::recursive_mutex>;

void register_handle(const void* object, HandleKind kind);
void unregister_handle(const void* object);
bool handle_is(const void* object, HandleKind kind);

template <class T, class H>
T* lookup(H handle) {
  T* p = reinterpret_cast<T*>(handle);
  return (p != nullptr && handle_is(p, T::kKind)) ? p : nullptr;
}
template <class H, class T>
H to_handle(T* object) {
  return reinterpret_cast<H>(object);
}

XrTime monotonic_now();

struct Session;
struct ActionSet;
struct Action;

struct Instance {
  static constexpr HandleKind kKind = HandleKind::instance;
  Config config;
  XrTime created = 0;                         // monotonic_now() at xrCreateInstance
  std::shared_ptr<const InputScript> script;  // null: real-time clock, no scripted input
  std::set<std::string> extensions;
  std::string application_name;
  bool system_queried = false;
  bool headset_gone = false;  // stays-lost: a scripted loss happened
  bool vk_requirements_queried = false;
  VkInstance vk_instance_created = VK_NULL_HANDLE;  // the last VkInstance made by xrCreateVulkanInstanceKHR
  std::deque<XrEventDataBuffer> events;
  std::vector<std::string> path_strings;  // XrPath p names path_strings[p - 1]
  std::unordered_map<std::string, XrPath> path_ids;
  std::vector<Session*> sessions;
  std::vector<ActionSet*> action_sets;
  // The scripted (virtual) clock goes on across the instance's sessions: a session created after one was
  // destroyed (a lost session recreated) starts where that one stopped, and the script's events already run
  // (the loss) do not run again.
  struct ScriptResume {
    XrTime clock_origin = 0;
    int64_t frames_waited = 0;
    std::size_t next_script_event = 0;
  };
  std::optional<ScriptResume> script_resume;
  // Suggested bindings per interaction profile: (action, component path).
  std::map<std::string, std::vector<std::pair<Action*, std::string>>> suggested;

  XrPath intern(const std::string& path);
  const std::string* path_string(XrPath path) const;
  void push_event(const XrEventDataBuffer& event);
};

struct VulkanBinding {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  uint32_t queue_index = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
};

struct HapticRecord {
  XrTime time;
  std::string path;  // the output it went to, e.g. /user/hand/left/output/haptic
  XrDuration duration;
  float frequency;
  float amplitude;
  bool stop;
};

struct Space;
struct Swapchain;

struct Session {
  static constexpr HandleKind kKind = HandleKind::session;
  Instance* instance = nullptr;
  VulkanBinding vk;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  bool exit_requested = false;
  bool loss_pending = false;
  XrViewConfigurationType view_configuration = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  XrPosef local_origin{};  // T_stage_local: the head at script time 0, gravity-aligned (yaw only)

  // Frame clock. Virtual (scripted): frame n is displayed at clock_origin + n * period.
  XrTime clock_origin = 0;
  XrDuration period = 0;
  int64_t frames_waited = 0;
  int64_t resume_frames = 0;  // frames_waited at xrBeginSession (Instance::script_resume)
  XrTime last_display_time = 0;
  XrTime next_real_vsync = 0;
  XrTime pace_origin = 0;  // PUSHPULL_XR_SIM_PACE: the real time of frame 0
  bool waited_not_begun = false;
  bool frame_begun = false;
  int64_t frames_ended = 0;
  std::condition_variable_any frame_cv;
  std::size_t next_script_event = 0;
  bool capture_requested = false;
  bool fail_next_begin = false;  // a scripted "failure": the next xrBeginFrame says XR_ERROR_RUNTIME_FAILURE
  bool lose_at_next_end = false;  // a scripted "lost": the next xrEndFrame says XR_ERROR_SESSION_LOST

  std::vector<Space*> spaces;
  std::vector<Swapchain*> swapchains;

  // Actions.
  std::vector<ActionSet*> attached;
  const InteractionProfile* profile = nullptr;  // current profile of both hands
  bool profile_event_pending = false;
  std::map<std::string, InputValue> overrides;  // XR_EXT_conformance_automation
  std::map<std::string, std::pair<Space*, XrPosef>> location_overrides;
  std::set<std::string> inactive_devices;  // top-level paths made inactive by automation
  std::vector<HapticRecord> haptics;

  bool is_virtual_clock() const { return instance->script != nullptr; }
  // Seconds of script time at XrTime t.
  double script_time(XrTime t) const { return static_cast<double>(t - clock_origin) * 1e-9; }
  // The time input is sampled at by xrSyncActions: the newest predicted display time (virtual clock)
  // or now (real time).
  XrTime input_time() const;
  void set_state(XrSessionState next, XrTime time);
};

struct Space {
  static constexpr HandleKind kKind = HandleKind::space;
  Session* session = nullptr;
  bool is_action_space = false;
  XrReferenceSpaceType reference = XR_REFERENCE_SPACE_TYPE_STAGE;
  Action* action = nullptr;
  XrPath subaction = XR_NULL_PATH;
  XrPosef offset{};  // T_space-origin_space (poseInReferenceSpace / poseInActionSpace)
};

struct ActionState {
  float x = 0.f;
  float y = 0.f;
  bool active = false;
  bool changed = false;
  XrTime last_change = 0;
};

struct Action {
  static constexpr HandleKind kKind = HandleKind::action;
  ActionSet* set = nullptr;
  std::string name;
  std::string localized_name;
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::vector<XrPath> subactions;
  std::vector<std::string> bound;        // component paths in the session's current profile
  std::map<XrPath, ActionState> states;  // per subaction path; XR_NULL_PATH: all combined
};

struct ActionSet {
  static constexpr HandleKind kKind = HandleKind::action_set;
  Instance* instance = nullptr;
  std::string name;
  std::string localized_name;
  uint32_t priority = 0;
  std::vector<Action*> actions;
  Session* attached_to = nullptr;
};

struct Swapchain {
  static constexpr HandleKind kKind = HandleKind::swapchain;
  Session* session = nullptr;
  XrSwapchainCreateInfo info{};
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::vector<VkImage> images;
  std::vector<VkDeviceMemory> memory;
  std::deque<uint32_t> acquired;  // acquired, not yet released, in acquire order
  bool wait_timed_out = false;    // quirk wait-timeout: this acquire's first wait returned XR_TIMEOUT_EXPIRED
  bool waited = false;            // acquired.front() has been waited on
  uint32_t next_index = 0;
  int64_t last_released = -1;
  bool static_used = false;
  std::vector<bool> laid_out;  // image i moved from UNDEFINED to its attachment layout (at first acquire)
};

// Destroys a session and everything it owns (spaces, swapchains); caller holds big_lock().
void destroy_session(Session* session);
// Destroys an action set and its actions; caller holds big_lock().
void destroy_action_set(ActionSet* set);
// Destroys a space / swapchain and removes it from its session; caller holds big_lock().
void destroy_space(Space* space);
void destroy_swapchain(Swapchain* swapchain);

// Session helpers shared by the areas (caller holds big_lock()).
// Checks a session handle; returns XR_ERROR_HANDLE_INVALID when it is not a live session.
XrResult get_session(XrSession handle, Session** out);
// Runs the script events due at or before `now` (exit, loss, capture, recenter) and queues their events.
void run_script_events(Session& session, XrTime now);
// Starts the runtime-initiated or app-requested exit: steps the state down to STOPPING.
void begin_exit(Session& session, XrTime now);
// The current interaction profile (after attach) and the action states at xrSyncActions.
void choose_interaction_profile(Session& session);

}  // namespace pushpull::xrsim
