// XR_EXT_conformance_automation: tests drive the simulated devices directly. Values and locations set
// here override the input script until the session ends; a device made inactive stops tracking and
// its actions become inactive at the next xrSyncActions.
#include "dispatch.hpp"
#include "input.hpp"
#include "sim_math.hpp"

namespace pushpull::xrsim {
namespace {

XrResult check_paths(Session& s, XrPath top_level, XrPath source, std::string* source_out) {
  const std::string* top = s.instance->path_string(top_level);
  if (top == nullptr) return XR_ERROR_PATH_INVALID;
  if (top_level_path(*top) != *top) return XR_ERROR_PATH_UNSUPPORTED;
  const std::string* src = s.instance->path_string(source);
  if (src == nullptr) return XR_ERROR_PATH_INVALID;
  if (top_level_path(*src) != *top) return XR_ERROR_PATH_UNSUPPORTED;
  *source_out = *src;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL set_active(XrSession handle, XrPath profile_path, XrPath top_level, XrBool32 is_active) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  const std::string* profile = s->instance->path_string(profile_path);
  const std::string* top = s->instance->path_string(top_level);
  if (profile == nullptr || top == nullptr) return XR_ERROR_PATH_INVALID;
  if (find_profile(*profile) == nullptr || top_level_path(*top) != *top) return XR_ERROR_PATH_UNSUPPORTED;
  if (is_active) {
    s->inactive_devices.erase(*top);
    if (!s->attached.empty() && (s->profile == nullptr || s->profile->path != *profile)) {
      s->instance->config.profile = *profile;
      choose_interaction_profile(*s);
    }
  } else {
    s->inactive_devices.insert(*top);
  }
  return XR_SUCCESS;
}

XrResult set_value(XrSession handle, XrPath top_level, XrPath source, InputValue value, bool vector) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  std::string path;
  if (const XrResult r = check_paths(*s, top_level, source, &path); XR_FAILED(r)) return r;
  s->overrides[path] = value;
  if (vector) {
    s->overrides[path + "/x"] = {value.x, 0.f};
    s->overrides[path + "/y"] = {value.y, 0.f};
  }
  return XR_SUCCESS;
}

XrResult XRAPI_CALL set_bool(XrSession h, XrPath top, XrPath source, XrBool32 state) {
  return set_value(h, top, source, {state ? 1.f : 0.f, 0.f}, false);
}
XrResult XRAPI_CALL set_float(XrSession h, XrPath top, XrPath source, float state) {
  return set_value(h, top, source, {state, 0.f}, false);
}
XrResult XRAPI_CALL set_vector2(XrSession h, XrPath top, XrPath source, XrVector2f state) {
  return set_value(h, top, source, {state.x, state.y}, true);
}

XrResult XRAPI_CALL set_location(XrSession handle, XrPath top_level, XrPath source, XrSpace space_handle,
                                 XrPosef pose) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  std::string path;
  if (const XrResult r = check_paths(*s, top_level, source, &path); XR_FAILED(r)) return r;
  Space* space = lookup<Space>(space_handle);
  if (space == nullptr || space->session != s) return XR_ERROR_HANDLE_INVALID;
  if (!quat_is_unit(pose.orientation)) return XR_ERROR_POSE_INVALID;
  const auto base = space_in_stage(*s, *space, s->input_time());
  if (!base) return XR_ERROR_VALIDATION_FAILURE;  // the space cannot be located now
  const std::string key = top_level_path(path) == "/user/head" ? std::string("/user/head") : path;
  s->location_overrides[key] = {space, pose_mul(*base, pose)};
  return XR_SUCCESS;
}

}  // namespace

void add_automation_functions(FunctionTable& t) {
  const char* e = XR_EXT_CONFORMANCE_AUTOMATION_EXTENSION_NAME;
  PUSHPULL_XR_ADD_EXT(t, xrSetInputDeviceActiveEXT, set_active, e);
  PUSHPULL_XR_ADD_EXT(t, xrSetInputDeviceStateBoolEXT, set_bool, e);
  PUSHPULL_XR_ADD_EXT(t, xrSetInputDeviceStateFloatEXT, set_float, e);
  PUSHPULL_XR_ADD_EXT(t, xrSetInputDeviceStateVector2fEXT, set_vector2, e);
  PUSHPULL_XR_ADD_EXT(t, xrSetInputDeviceLocationEXT, set_location, e);
}

}  // namespace pushpull::xrsim
