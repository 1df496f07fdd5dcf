// pushpull::xr::Input: the review's action set and its bindings for the interaction profiles of OpenXR 1.0
// (khr/simple, oculus/touch, valve/index, htc/vive, microsoft/motion) and of three controller extensions,
// suggested where the session enabled them (hp/mixed_reality_controller: HP Reverb G2;
// htc/vive_cosmos_controller; samsung/odyssey_controller), synced once per frame.
//
// Actions per hand (subaction paths /user/hand/left and /user/hand/right):
//   trigger (push/pull; simple: select/click), grip (squeeze), aim pose, thumbstick (vive: trackpad),
//   undo, redo (touch, hp, cosmos: X/A = undo, Y/B = redo; index: A = undo, B = redo; simple, vive, motion,
//   odyssey: left menu = undo, right menu = redo), menu (touch, cosmos: left menu; hp: either menu; index:
//   thumbstick click; vive: trackpad click; motion, odyssey: thumbstick click) and a haptic output.
// A profile the runtime refuses (XR_ERROR_PATH_UNSUPPORTED, ...) is skipped with a warning on stderr.
//
// Frames: aim poses are T_stage_aim (metres, the stage space given), the ray leaves along the pose's -Z.
// Ownership: owns the action set, actions and action spaces; borrows the instance, session and stage space
// (the Session outlives the Input). Thread-safety: one thread (the frame loop).
#pragma once

#include "pushpull/xr/xr_check.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pushpull::xr {

enum class Hand { Left = 0, Right = 1 };

// The review's actions read from a controller component (the aim pose and the haptic output aside).
enum class BoundAction { Trigger, Grip, Thumbstick, Undo, Redo, Menu };

// The component below the hand's user path ("/input/trigger/value") Input suggests for `action` on `hand`
// in the interaction profile `profile` ("/interaction_profiles/oculus/touch_controller"); "" where it
// suggests none (the profile has no such control on that hand, or is not one Input knows). A recording
// writes a hand's state to these components, so its replay presses what the headset pressed. Pure.
[[nodiscard]] std::string suggested_component(const std::string& profile, BoundAction action, Hand hand);

// The OpenXR instance extensions that bring interaction profiles Input suggests bindings for: a Session
// enables those its runtime offers (SessionOptions::controller_extensions). Immutable.
[[nodiscard]] const std::vector<std::string>& controller_profile_extensions();

struct HandInput {
  float trigger = 0.0f;  // 0..1
  float grip = 0.0f;     // 0..1
  XrVector2f thumbstick{0.0f, 0.0f};
  std::optional<XrPosef> T_stage_aim;  // none when not located
  // The aim's position is tracked, not the runtime's guess (a controller out of its tracking cameras' view is
  // still located, with XR_SPACE_LOCATION_POSITION_TRACKED_BIT clear). Meaningful with T_stage_aim.
  bool aim_position_tracked = true;
  bool undo_pressed = false;  // went down since the last sync
  bool redo_pressed = false;
  bool menu_pressed = false;
};

class Input {
 public:
  // enabled_extensions: the instance's enabled extensions (Session::enabled_extensions()); a profile an
  // extension brings is suggested only when its extension is among them.
  Input(XrInstance instance, XrSession session, XrSpace stage_space,
        const std::vector<std::string>& enabled_extensions = {});
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // xrSyncActions and every action's state at `time` (the frame's predicted display time). Only call
  // while the session is running; when it is not focused every input reads as released.
  void sync(XrTime time);
  [[nodiscard]] const HandInput& hand(Hand hand) const;
  // A short vibration (amplitude 0..1, duration in seconds) on that hand's controller. Best effort: a failure
  // is noted once per Input on stderr and otherwise ignored (a lost session shows at the next frame).
  void haptic_pulse(Hand hand, float amplitude, double duration_s);
  // The interaction profile the runtime chose for the hand ("" when none yet, or when the query fails: noted
  // once per Input on stderr).
  [[nodiscard]] std::string current_profile(Hand hand) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::xr
