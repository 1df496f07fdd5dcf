// pushpull::xr::Session: an OpenXR instance, system, Vulkan device (XR_KHR_vulkan_enable2, or
// XR_KHR_vulkan_enable with a runtime that offers only the first binding), session, the
// stage space and one swapchain per eye, with the session state machine and the frame calls.
//
//   Session xr(options);                     // throws RuntimeUnavailable when there is no runtime / HMD
//   renderer::Context::wrap(xr.vulkan());    // app/: xr never includes the renderer
//   while (!xr.exit_requested()) {
//     xr.poll_events();                      // READY -> xrBeginSession, STOPPING -> xrEndSession, ...
//     if (!xr.running()) { sleep a little; continue; }
//     FrameViews f = xr.begin_frame();       // xrWaitFrame + xrBeginFrame + xrLocateViews (stage space)
//     if (f.should_render) { index = xr.eye(i).acquire(); draw; }   // both eyes
//     xr.end_frame(f, rendered);             // releases the images, submits one projection layer
//   }
//
// State machine: READY begins the session (PRIMARY_STEREO); STOPPING ends it; EXITING, LOSS_PENDING and
// instance loss request exit; a frame call that fails with XR_ERROR_SESSION_LOST marks the session lost.
// lost() tells the app to drop what the session was doing (a drag is cancelled, not committed).
//
// Frames: poses are T_stage_eye (stage space: STAGE when the runtime has it, LOCAL otherwise; metres, +Y up,
// -Z forward). Ownership: owns every handle it creates (the Vulkan instance and device too: destroyed after
// the session, before the XrInstance); keep everything made from vulkan() shorter-lived than the Session.
// Move-only. Thread-safety: one thread (the frame loop) for every call.
#pragma once

#include "pushpull/xr/swapchain.hpp"
#include "pushpull/xr/xr_check.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pushpull::xr {

// xrCreateInstance or xrGetSystem failed: no OpenXR runtime installed or active, or no headset. what() is one
// line naming the runtime the loader looked for and how to point it at one (XR_RUNTIME_JSON).
class RuntimeUnavailable : public XrError {
 public:
  using XrError::XrError;
};

struct SessionOptions {
  std::string application_name = "pushpull";
  // Called before the runtime creates the Vulkan device, on the Vulkan 1.3 feature struct chained into
  // VkDeviceCreateInfo (the renderer's Context::require_features).
  std::function<void(VkPhysicalDeviceVulkan13Features&)> require_vulkan13_features;
  // Vulkan extensions beyond the runtime's own (e.g. a mirror window's surface extensions and
  // VK_KHR_swapchain): added to the create infos handed to xrCreateVulkanInstanceKHR /
  // xrCreateVulkanDeviceKHR (XR_KHR_vulkan_enable2), or, with a runtime that offers only
  // XR_KHR_vulkan_enable, enabled with the extensions that runtime names in the instance and device the
  // Session creates itself.
  std::vector<std::string> vulkan_instance_extensions;
  std::vector<std::string> vulkan_device_extensions;
  std::vector<std::string> vulkan_layers;  // instance layers, e.g. VK_LAYER_KHRONOS_validation
  // Per-eye image size; 0 = the runtime's recommended size (the larger of the two eyes', so both eyes share
  // one size), never more than the smaller of the two eyes' maxima.
  uint32_t eye_width = 0, eye_height = 0;
  // Eye swapchains with transfer-source usage, so a mirror window can copy an eye (Swapchain::transfer_source
  // says whether the runtime allowed it). Off: colour attachment only, which every runtime supports.
  bool eye_transfer_source = false;
  // Extensions the session must enable beyond XR_KHR_vulkan_enable2 (or XR_KHR_vulkan_enable where the
  // runtime offers only that one) (e.g. for tests); unknown ones fail.
  std::vector<std::string> extensions;
  // A runtime whose headset is not connected yet (xrGetSystem: XR_ERROR_FORM_FACTOR_UNAVAILABLE, "temporarily
  // unavailable": streaming runtimes before the headset joins) is asked again for this many seconds before
  // the session gives up with RuntimeUnavailable.
  double headset_wait_s = 3.0;
};

// What the renderer borrows (renderer::ExternalVulkan has the same fields). Owned by the Session.
struct VulkanDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family_index = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

struct EyeView {
  XrPosef T_stage_eye{{0, 0, 0, 1}, {0, 0, 0}};  // metres
  XrFovf fov{};                                  // radians, left/down negative
};

struct FrameViews {
  XrTime predicted_display_time = 0;
  XrDuration predicted_display_period = 0;
  bool should_render = false;  // the runtime shows the frame and the views were located
  bool position_valid = false;  // with should_render: the eyes' positions too (else the last located ones)
  std::array<EyeView, 2> eyes{};
};

class Session {
 public:
  explicit Session(const SessionOptions& options = {});
  ~Session();
  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;

  // Handles pending events and runs the state machine. Never blocks.
  void poll_events();
  [[nodiscard]] bool running() const;         // begun and not ended: run frames
  [[nodiscard]] bool focused() const;         // XR_SESSION_STATE_FOCUSED: input is ours
  [[nodiscard]] bool exit_requested() const;  // leave the frame loop
  [[nodiscard]] bool lost() const;            // the session or the instance was lost
  [[nodiscard]] XrSessionState state() const;
  // Whether the runtime announced a change of the stage space (recentring, a new play area) since the last
  // call: stage coordinates jump at its change time, so a gesture spanning it is meaningless.
  [[nodiscard]] bool take_space_change();
  // How the runtime shows frames: OPAQUE (the usual headset), or ADDITIVE / ALPHA_BLEND on see-through
  // displays, where the eyes' background must be transparent black rather than a studio grey.
  [[nodiscard]] XrEnvironmentBlendMode blend_mode() const;
  // After a lost session (lost(), or a call that failed with XR_ERROR_SESSION_LOST): destroys the lost
  // session, polls xrGetSystem until the headset is back (XR_ERROR_FORM_FACTOR_UNAVAILABLE meanwhile) or
  // timeout_s passed, then creates the session, the stage space and the eye swapchains again on the same
  // instance and Vulkan device (eye(i) are new swapchains; an Input made for the old session must be made
  // again). Returns false when it cannot (instance lost, timeout, or give_up() said so: asked every 0.1 s
  // while waiting, e.g. a Ctrl-C); throws XrError when the headset came back as another system.
  bool recreate_after_loss(double timeout_s, const std::function<bool()>& give_up = {});
  // Asks the runtime to end the session (xrRequestExitSession); the loop goes on until exit_requested().
  void request_exit();

  // xrWaitFrame, xrBeginFrame, xrLocateViews. On XR_ERROR_SESSION_LOST: lost() and should_render = false.
  FrameViews begin_frame();
  // Releases the eye images still acquired and calls xrEndFrame, with one projection layer when `rendered`.
  void end_frame(const FrameViews& frame, bool rendered);

  [[nodiscard]] Swapchain& eye(int index);  // 0 = left, 1 = right
  [[nodiscard]] const VulkanDevice& vulkan() const;
  [[nodiscard]] XrInstance instance() const;
  [[nodiscard]] XrSession handle() const;
  [[nodiscard]] XrSpace stage_space() const;
  [[nodiscard]] bool stage_is_local() const;  // no STAGE space: LOCAL (floor unknown, head height guessed)
  [[nodiscard]] const std::string& runtime_name() const;
  [[nodiscard]] const std::string& system_name() const;
  // The instance's enabled extensions: the Vulkan binding, SessionOptions::extensions, and those of
  // controller_profile_extensions() (input.hpp) the runtime offers. For Input's constructor.
  [[nodiscard]] const std::vector<std::string>& enabled_extensions() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::xr
