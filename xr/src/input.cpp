#include "pushpull/xr/input.hpp"

#include "finite_pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

namespace pushpull::xr {
namespace {

enum ActionIndex { Trigger, Grip, Aim, Thumbstick, Undo, Redo, Menu, Haptic, ActionCount };

struct ActionSpec {
  const char* name;
  const char* localized;
  XrActionType type;
};
constexpr ActionSpec kActions[ActionCount] = {
    {"trigger", "Push/pull", XR_ACTION_TYPE_FLOAT_INPUT},
    {"grip", "Grab the model", XR_ACTION_TYPE_FLOAT_INPUT},
    {"aim", "Aim", XR_ACTION_TYPE_POSE_INPUT},
    {"thumbstick", "Handle and region size", XR_ACTION_TYPE_VECTOR2F_INPUT},
    {"undo", "Undo", XR_ACTION_TYPE_BOOLEAN_INPUT},
    {"redo", "Redo", XR_ACTION_TYPE_BOOLEAN_INPUT},
    {"menu", "Menu", XR_ACTION_TYPE_BOOLEAN_INPUT},
    {"haptic", "Haptic pulse", XR_ACTION_TYPE_VIBRATION_OUTPUT},
};

using Binding = std::pair<ActionIndex, const char*>;
struct Profile {
  const char* path;
  std::vector<Binding> bindings;
  const char* extension = nullptr;  // the instance extension that brings the profile (none: OpenXR 1.0 core)
};

// A binding's first character says which hands get its component: '*' both, 'L' the left, 'R' the right.
std::vector<Profile> profiles() {
  const std::vector<Binding> motion = {{Trigger, "*/input/trigger/value"}, {Grip, "*/input/squeeze/click"},
                                       {Aim, "*/input/aim/pose"},          {Thumbstick, "*/input/thumbstick"},
                                       {Undo, "L/input/menu/click"},       {Redo, "R/input/menu/click"},
                                       {Menu, "*/input/thumbstick/click"}, {Haptic, "*/output/haptic"}};
  return {
      {"/interaction_profiles/khr/simple_controller",
       {{Trigger, "*/input/select/click"},
        {Aim, "*/input/aim/pose"},
        {Undo, "L/input/menu/click"},
        {Redo, "R/input/menu/click"},
        {Haptic, "*/output/haptic"}}},
      {"/interaction_profiles/oculus/touch_controller",
       {{Trigger, "*/input/trigger/value"},
        {Grip, "*/input/squeeze/value"},
        {Aim, "*/input/aim/pose"},
        {Thumbstick, "*/input/thumbstick"},
        {Undo, "L/input/x/click"},
        {Undo, "R/input/a/click"},
        {Redo, "L/input/y/click"},
        {Redo, "R/input/b/click"},
        {Menu, "L/input/menu/click"},
        {Haptic, "*/output/haptic"}}},
      {"/interaction_profiles/valve/index_controller",
       {{Trigger, "*/input/trigger/value"},
        {Grip, "*/input/squeeze/value"},
        {Aim, "*/input/aim/pose"},
        {Thumbstick, "*/input/thumbstick"},
        {Undo, "*/input/a/click"},
        {Redo, "*/input/b/click"},
        {Menu, "*/input/thumbstick/click"},
        {Haptic, "*/output/haptic"}}},
      {"/interaction_profiles/htc/vive_controller",
       {{Trigger, "*/input/trigger/value"},
        {Grip, "*/input/squeeze/click"},
        {Aim, "*/input/aim/pose"},
        {Thumbstick, "*/input/trackpad"},
        {Undo, "L/input/menu/click"},
        {Redo, "R/input/menu/click"},
        {Menu, "*/input/trackpad/click"},
        {Haptic, "*/output/haptic"}}},
      {"/interaction_profiles/microsoft/motion_controller", motion},
      // HP Reverb G2: Touch's layout (X/Y left, A/B right), a menu button on each hand.
      {"/interaction_profiles/hp/mixed_reality_controller",
       {{Trigger, "*/input/trigger/value"},
        {Grip, "*/input/squeeze/value"},
        {Aim, "*/input/aim/pose"},
        {Thumbstick, "*/input/thumbstick"},
        {Undo, "L/input/x/click"},
        {Undo, "R/input/a/click"},
        {Redo, "L/input/y/click"},
        {Redo, "R/input/b/click"},
        {Menu, "*/input/menu/click"},
        {Haptic, "*/output/haptic"}},
       XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME},
      {"/interaction_profiles/htc/vive_cosmos_controller",
       {{Trigger, "*/input/trigger/value"},
        {Grip, "*/input/squeeze/click"},
        {Aim, "*/input/aim/pose"},
        {Thumbstick, "*/input/thumbstick"},
        {Undo, "L/input/x/click"},
        {Undo, "R/input/a/click"},
        {Redo, "L/input/y/click"},
        {Redo, "R/input/b/click"},
        {Menu, "L/input/menu/click"},
        {Haptic, "*/output/haptic"}},
       XR_HTC_VIVE_COSMOS_CONTROLLER_INTERACTION_EXTENSION_NAME},
      // Samsung Odyssey: the Windows Mixed Reality motion controller's components.
      {"/interaction_profiles/samsung/odyssey_controller", motion,
       XR_EXT_SAMSUNG_ODYSSEY_CONTROLLER_EXTENSION_NAME},
  };
}

const std::vector<Profile>& known_profiles() {
  static const std::vector<Profile> all = profiles();
  return all;
}

constexpr const char* kHandPaths[2] = {"/user/hand/left", "/user/hand/right"};

}  // namespace

std::string suggested_component(const std::string& profile, BoundAction action, Hand hand) {
  ActionIndex index = Trigger;
  switch (action) {
    case BoundAction::Trigger:
      index = Trigger;
      break;
    case BoundAction::Grip:
      index = Grip;
      break;
    case BoundAction::Thumbstick:
      index = Thumbstick;
      break;
    case BoundAction::Undo:
      index = Undo;
      break;
    case BoundAction::Redo:
      index = Redo;
      break;
    case BoundAction::Menu:
      index = Menu;
      break;
  }
  const char own = hand == Hand::Left ? 'L' : 'R';
  for (const Profile& p : known_profiles()) {
    if (profile != p.path) continue;
    for (const auto& [bound, component] : p.bindings)
      if (bound == index && (component[0] == '*' || component[0] == own)) return component + 1;
    return {};
  }
  return {};
}

const std::vector<std::string>& controller_profile_extensions() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Profile& p : known_profiles())
      if (p.extension != nullptr) list.emplace_back(p.extension);
    return list;
  }();
  return names;
}

struct Input::Impl {
  XrInstance instance = XR_NULL_HANDLE;
  XrSession session = XR_NULL_HANDLE;
  XrSpace stage = XR_NULL_HANDLE;
  XrActionSet set = XR_NULL_HANDLE;
  XrAction actions[ActionCount] = {};
  XrPath hands[2] = {};
  XrSpace aim_spaces[2] = {};
  HandInput state[2];
  bool haptics_failed = false, profile_failed = false;  // said once; the review goes on without them

  // A failed optional call (haptics, the profile query) is reported once on stderr and otherwise ignored:
  // runtimes fail them transiently (XR_ERROR_RUNTIME_FAILURE) and a lost session shows at the next frame.
  void optional_call_failed(bool& said, const char* what, XrResult r) {
    if (said) return;
    said = true;
    std::fprintf(stderr, "pushpull: note: %s failed (%s); going on without it\n", what,
                 result_name(instance, r).c_str());
  }

  ~Impl() {
    for (XrSpace s : aim_spaces)
      if (s != XR_NULL_HANDLE) xrDestroySpace(s);
    // xrDestroyActionSet destroys its actions, but the OpenXR core validation layer (1.0.20) keeps tracking
    // them: when a new session's action set reuses an old action's handle value (xr/sim's handles are
    // addresses) the layer failed xrCreateAction with "Handle ... already inserted" (XR_ERROR_VALIDATION_
    // FAILURE) after a lost session. Destroying them one by one first keeps its tracking right.
    for (XrAction& a : actions)
      if (a != XR_NULL_HANDLE) xrDestroyAction(a);
    if (set != XR_NULL_HANDLE) xrDestroyActionSet(set);
  }

  XrPath path(const std::string& text) const {
    XrPath p = XR_NULL_PATH;
    PUSHPULL_XR_CHECK(instance, xrStringToPath(instance, text.c_str(), &p));
    return p;
  }

  XrActionStateGetInfo get_info(ActionIndex action, int hand) const {
    XrActionStateGetInfo info{XR_TYPE_ACTION_STATE_GET_INFO};
    info.action = actions[action];
    info.subactionPath = hands[hand];
    return info;
  }

  bool pressed_now(ActionIndex action, int hand) const {
    const XrActionStateGetInfo info = get_info(action, hand);
    XrActionStateBoolean s{XR_TYPE_ACTION_STATE_BOOLEAN};
    PUSHPULL_XR_CHECK(instance, xrGetActionStateBoolean(session, &info, &s));
    return s.isActive && s.changedSinceLastSync && s.currentState;
  }
  float value(ActionIndex action, int hand) const {
    const XrActionStateGetInfo info = get_info(action, hand);
    XrActionStateFloat s{XR_TYPE_ACTION_STATE_FLOAT};
    PUSHPULL_XR_CHECK(instance, xrGetActionStateFloat(session, &info, &s));
    return s.isActive ? in_range(s.currentState, 0.0f) : 0.0f;
  }
  // A float action's value as the specification bounds it (triggers and grips 0..1, thumbstick axes -1..1):
  // a runtime's out-of-range or non-finite value (one gave 1e308, an infinity as a float) reads as the
  // nearest bound, or as released, instead of reaching the gesture and the recording (which wrote it as
  // null).
  static float in_range(float value, float low) {
    if (!std::isfinite(value)) return 0.0f;
    return std::clamp(value, low, 1.0f);
  }
};

Input::Input(XrInstance instance, XrSession session, XrSpace stage_space,
             const std::vector<std::string>& enabled_extensions)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.instance = instance;
  s.session = session;
  s.stage = stage_space;
  XrActionSetCreateInfo set_info{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(set_info.actionSetName, "review");
  std::strcpy(set_info.localizedActionSetName, "Design review");
  PUSHPULL_XR_CHECK(instance, xrCreateActionSet(instance, &set_info, &s.set));
  for (int h = 0; h < 2; ++h) s.hands[h] = s.path(kHandPaths[h]);
  for (int a = 0; a < ActionCount; ++a) {
    XrActionCreateInfo info{XR_TYPE_ACTION_CREATE_INFO};
    std::strcpy(info.actionName, kActions[a].name);
    std::strcpy(info.localizedActionName, kActions[a].localized);
    info.actionType = kActions[a].type;
    info.countSubactionPaths = 2;
    info.subactionPaths = s.hands;
    PUSHPULL_XR_CHECK(instance, xrCreateAction(s.set, &info, &s.actions[a]));
  }
  for (const Profile& profile : known_profiles()) {
    // A profile an extension brings exists for the runtime only with that extension enabled.
    if (profile.extension != nullptr && std::find(enabled_extensions.begin(), enabled_extensions.end(),
                                                  profile.extension) == enabled_extensions.end())
      continue;
    std::vector<XrActionSuggestedBinding> suggested;
    for (const auto& [action, component] : profile.bindings) {
      const char which = component[0];
      for (int h = 0; h < 2; ++h) {
        if ((which == 'L' && h != 0) || (which == 'R' && h != 1)) continue;
        suggested.push_back({s.actions[action], s.path(std::string(kHandPaths[h]) + (component + 1))});
      }
    }
    XrInteractionProfileSuggestedBinding info{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
    info.interactionProfile = s.path(profile.path);
    info.countSuggestedBindings = uint32_t(suggested.size());
    info.suggestedBindings = suggested.data();
    if (const XrResult r = xrSuggestInteractionProfileBindings(instance, &info); XR_FAILED(r))
      std::fprintf(stderr,
                   "pushpull: warning: the OpenXR runtime refused the bindings for %s (%s); skipped\n",
                   profile.path, result_name(instance, r).c_str());
  }
  for (int h = 0; h < 2; ++h) {
    XrActionSpaceCreateInfo info{XR_TYPE_ACTION_SPACE_CREATE_INFO};
    info.action = s.actions[Aim];
    info.subactionPath = s.hands[h];
    info.poseInActionSpace.orientation.w = 1.0f;
    PUSHPULL_XR_CHECK(instance, xrCreateActionSpace(session, &info, &s.aim_spaces[h]));
  }
  XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
  attach.countActionSets = 1;
  attach.actionSets = &s.set;
  PUSHPULL_XR_CHECK(instance, xrAttachSessionActionSets(session, &attach));
}

Input::~Input() = default;

void Input::sync(XrTime time) {
  Impl& s = *impl_;
  XrActiveActionSet active{s.set, XR_NULL_PATH};
  XrActionsSyncInfo sync{XR_TYPE_ACTIONS_SYNC_INFO};
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  const XrResult r = PUSHPULL_XR_CHECK(s.instance, xrSyncActions(s.session, &sync));
  for (int h = 0; h < 2; ++h) {
    HandInput& in = s.state[h];
    const std::optional<XrPosef> last_aim = in.T_stage_aim;
    in = HandInput{};
    if (r == XR_SESSION_NOT_FOCUSED) continue;  // everything reads as released
    in.trigger = s.value(Trigger, h);
    in.grip = s.value(Grip, h);
    in.undo_pressed = s.pressed_now(Undo, h);
    in.redo_pressed = s.pressed_now(Redo, h);
    in.menu_pressed = s.pressed_now(Menu, h);
    {
      const XrActionStateGetInfo info = s.get_info(Thumbstick, h);
      XrActionStateVector2f v{XR_TYPE_ACTION_STATE_VECTOR2F};
      PUSHPULL_XR_CHECK(s.instance, xrGetActionStateVector2f(s.session, &info, &v));
      if (v.isActive)
        in.thumbstick = {Impl::in_range(v.currentState.x, -1.0f), Impl::in_range(v.currentState.y, -1.0f)};
    }
    XrSpaceLocation location{XR_TYPE_SPACE_LOCATION};
    PUSHPULL_XR_CHECK(s.instance, xrLocateSpace(s.aim_spaces[h], s.stage, time, &location));
    const XrSpaceLocationFlags valid =
        XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT;
    if ((location.locationFlags & valid) == valid) {
      if (detail::finite_pose(location.pose)) {
        in.T_stage_aim = location.pose;
        in.aim_position_tracked = (location.locationFlags & XR_SPACE_LOCATION_POSITION_TRACKED_BIT) != 0;
      } else if (last_aim) {
        // Valid but not finite (a runtime's overflow, a driver's glitch): the hand stays where it was last
        // located, as a controller out of its cameras' view does, and never feeds inf or NaN further.
        in.T_stage_aim = last_aim;
        in.aim_position_tracked = false;
      }
    }
  }
}

const HandInput& Input::hand(Hand hand) const {
  return impl_->state[int(hand)];
}

void Input::haptic_pulse(Hand hand, float amplitude, double duration_s) {
  Impl& s = *impl_;
  XrHapticActionInfo info{XR_TYPE_HAPTIC_ACTION_INFO};
  info.action = s.actions[Haptic];
  info.subactionPath = s.hands[int(hand)];
  XrHapticVibration vibration{XR_TYPE_HAPTIC_VIBRATION};
  vibration.amplitude = amplitude;
  vibration.duration = XrDuration(duration_s * 1e9);
  vibration.frequency = XR_FREQUENCY_UNSPECIFIED;
  const XrResult r =
      xrApplyHapticFeedback(s.session, &info, reinterpret_cast<const XrHapticBaseHeader*>(&vibration));
  if (XR_FAILED(r)) s.optional_call_failed(s.haptics_failed, "xrApplyHapticFeedback", r);
}

std::string Input::current_profile(Hand hand) const {
  Impl& s = *impl_;
  XrInteractionProfileState state{XR_TYPE_INTERACTION_PROFILE_STATE};
  XrResult r = xrGetCurrentInteractionProfile(s.session, s.hands[int(hand)], &state);
  if (XR_SUCCEEDED(r) && state.interactionProfile == XR_NULL_PATH) return "";
  char text[XR_MAX_PATH_LENGTH] = {};
  uint32_t n = 0;
  if (XR_SUCCEEDED(r)) r = xrPathToString(s.instance, state.interactionProfile, sizeof text, &n, text);
  if (XR_FAILED(r)) {
    s.optional_call_failed(s.profile_failed, "xrGetCurrentInteractionProfile", r);
    return "";
  }
  return text;
}

}  // namespace pushpull::xr
