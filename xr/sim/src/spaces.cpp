// Reference spaces (VIEW, LOCAL, STAGE with bounds), action spaces, xrLocateSpace and xrLocateViews.
// Eyes sit ipd/2 either side of the head along its +X; each eye's FOV is asymmetric (wider outwards
// and downwards), mirrored between the eyes.
#include "dispatch.hpp"
#include "input.hpp"
#include "sim_math.hpp"

#include <algorithm>
#include <cmath>

namespace pushpull::xrsim {

void destroy_space(Space* space) {
  auto& list = space->session->spaces;
  list.erase(std::remove(list.begin(), list.end(), space), list.end());
  unregister_handle(space);
  delete space;
}

namespace {

constexpr float kStageWidth = 4.f;  // meters along X
constexpr float kStageDepth = 3.f;  // meters along Z

XrResult check_reference_type(XrReferenceSpaceType t) {
  if (t == XR_REFERENCE_SPACE_TYPE_VIEW || t == XR_REFERENCE_SPACE_TYPE_LOCAL ||
      t == XR_REFERENCE_SPACE_TYPE_STAGE)
    return XR_SUCCESS;
  if (t == XR_REFERENCE_SPACE_TYPE_UNBOUNDED_MSFT || t == XR_REFERENCE_SPACE_TYPE_COMBINED_EYE_VARJO)
    return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
  return XR_ERROR_VALIDATION_FAILURE;
}

XrResult XRAPI_CALL enumerate_reference_spaces(XrSession handle, uint32_t capacity, uint32_t* count,
                                               XrReferenceSpaceType* spaces) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (capacity != 0 && spaces == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  static constexpr XrReferenceSpaceType kTypes[] = {
      XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL, XR_REFERENCE_SPACE_TYPE_STAGE};
  return two_call(capacity, count, 3, [&](uint32_t i) { spaces[i] = kTypes[i]; });
}

XrResult XRAPI_CALL create_reference_space(XrSession handle, const XrReferenceSpaceCreateInfo* info,
                                           XrSpace* out) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_REFERENCE_SPACE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_reference_type(info->referenceSpaceType); XR_FAILED(r)) return r;
  if (!quat_is_unit(info->poseInReferenceSpace.orientation)) return XR_ERROR_POSE_INVALID;
  auto* space = new Space;
  space->session = s;
  space->reference = info->referenceSpaceType;
  space->offset = info->poseInReferenceSpace;
  space->offset.orientation = quat_normalize(space->offset.orientation);
  register_handle(space, HandleKind::space);
  s->spaces.push_back(space);
  *out = to_handle<XrSpace>(space);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_bounds(XrSession handle, XrReferenceSpaceType type, XrExtent2Df* bounds) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (bounds == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_reference_type(type); XR_FAILED(r)) return r;
  if (type != XR_REFERENCE_SPACE_TYPE_STAGE) {
    *bounds = {0.f, 0.f};
    return XR_SPACE_BOUNDS_UNAVAILABLE;
  }
  *bounds = {kStageWidth, kStageDepth};
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_action_space(XrSession handle, const XrActionSpaceCreateInfo* info, XrSpace* out) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_ACTION_SPACE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  Action* action = lookup<Action>(info->action);
  if (action == nullptr || action->set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
  if (action->type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  if (info->subactionPath != XR_NULL_PATH) {
    if (s->instance->path_string(info->subactionPath) == nullptr) return XR_ERROR_PATH_INVALID;
    if (std::find(action->subactions.begin(), action->subactions.end(), info->subactionPath) ==
        action->subactions.end())
      return XR_ERROR_PATH_UNSUPPORTED;
  }
  if (!quat_is_unit(info->poseInActionSpace.orientation)) return XR_ERROR_POSE_INVALID;
  auto* space = new Space;
  space->session = s;
  space->is_action_space = true;
  space->action = action;
  space->subaction = info->subactionPath;
  space->offset = info->poseInActionSpace;
  space->offset.orientation = quat_normalize(space->offset.orientation);
  register_handle(space, HandleKind::space);
  s->spaces.push_back(space);
  *out = to_handle<XrSpace>(space);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_space_entry(XrSpace handle) {
  Lock lock(big_lock());
  Space* space = lookup<Space>(handle);
  if (space == nullptr) return XR_ERROR_HANDLE_INVALID;
  destroy_space(space);
  return XR_SUCCESS;
}

constexpr XrSpaceLocationFlags kAllValid =
    XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
    XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;

// T_base_space at `time`, or nullopt.
std::optional<XrPosef> relative_pose(const Session& s, const Space& space, const Space& base, XrTime time) {
  const auto a = space_in_stage(s, space, time);
  const auto b = space_in_stage(s, base, time);
  if (!a || !b) return std::nullopt;
  return pose_mul(pose_inverse(*b), *a);
}

XrResult XRAPI_CALL locate_space(XrSpace space_handle, XrSpace base_handle, XrTime time,
                                 XrSpaceLocation* location) {
  Lock lock(big_lock());
  Space* space = lookup<Space>(space_handle);
  Space* base = lookup<Space>(base_handle);
  if (space == nullptr || base == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (location == nullptr || location->type != XR_TYPE_SPACE_LOCATION) return XR_ERROR_VALIDATION_FAILURE;
  if (space->session != base->session) return XR_ERROR_VALIDATION_FAILURE;
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  const Session& s = *space->session;
  XrSpaceVelocity* velocity = nullptr;
  for (auto* h = static_cast<XrBaseOutStructure*>(location->next); h != nullptr; h = h->next)
    if (h->type == XR_TYPE_SPACE_VELOCITY) velocity = reinterpret_cast<XrSpaceVelocity*>(h);
  const auto pose = relative_pose(s, *space, *base, time);
  if (!pose) {
    location->locationFlags = 0;
    location->pose = pose_identity();
    if (velocity != nullptr) velocity->velocityFlags = 0;
    return XR_SUCCESS;
  }
  location->locationFlags = kAllValid;
  if (!space_position_tracked(s, *space, time) || !space_position_tracked(s, *base, time))
    location->locationFlags &= ~XrSpaceLocationFlags(XR_SPACE_LOCATION_POSITION_TRACKED_BIT);
  location->pose = *pose;
  if (velocity != nullptr) {
    // Central differences over +-5 ms of the (deterministic) pose function.
    const XrDuration dt = 5000000;
    const auto before = relative_pose(s, *space, *base, time - dt);
    const auto after = relative_pose(s, *space, *base, time + dt);
    velocity->velocityFlags = 0;
    velocity->linearVelocity = {0.f, 0.f, 0.f};
    velocity->angularVelocity = {0.f, 0.f, 0.f};
    if (before && after) {
      const float inv = 1.f / (2.f * static_cast<float>(dt) * 1e-9f);
      velocity->linearVelocity = {(after->position.x - before->position.x) * inv,
                                  (after->position.y - before->position.y) * inv,
                                  (after->position.z - before->position.z) * inv};
      XrQuaternionf dq = quat_mul(after->orientation, quat_conj(before->orientation));
      if (dq.w < 0) dq = {-dq.x, -dq.y, -dq.z, -dq.w};
      velocity->angularVelocity = {2.f * dq.x * inv, 2.f * dq.y * inv, 2.f * dq.z * inv};
      velocity->velocityFlags = XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT;
    }
  }
  return XR_SUCCESS;
}

XrResult XRAPI_CALL locate_views(XrSession handle, const XrViewLocateInfo* info, XrViewState* state,
                                 uint32_t capacity, uint32_t* count, XrView* views) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || state == nullptr || count == nullptr || info->type != XR_TYPE_VIEW_LOCATE_INFO ||
      state->type != XR_TYPE_VIEW_STATE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
    const XrViewConfigurationType t = info->viewConfigurationType;
    const bool known = t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO ||
                       t == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO ||
                       t == XR_VIEW_CONFIGURATION_TYPE_SECONDARY_MONO_FIRST_PERSON_OBSERVER_MSFT;
    return known ? XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED : XR_ERROR_VALIDATION_FAILURE;
  }
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  const Space* base = lookup<Space>(info->space);
  if (base == nullptr || base->session != s) return XR_ERROR_HANDLE_INVALID;
  if (capacity != 0 && views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < capacity; ++i)
    if (views[i].type != XR_TYPE_VIEW) return XR_ERROR_VALIDATION_FAILURE;
  const auto base_pose = space_in_stage(*s, *base, info->displayTime);
  state->viewStateFlags = base_pose ? kAllValid : 0;
  // position-late: tracking finds the room a moment after the headset's orientation (10 frames).
  if (s->instance->config.rotation_only || (s->instance->config.position_late && s->frames_waited <= 10))
    state->viewStateFlags &=
        ~XrViewStateFlags(XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_POSITION_TRACKED_BIT);
  const XrPosef head = head_pose(*s, info->displayTime);
  const float half_ipd = s->instance->config.ipd_m * 0.5f;
  return two_call(capacity, count, 2, [&](uint32_t i) {
    const float side = i == 0 ? -1.f : 1.f;
    XrPosef eye_in_head = pose_identity();
    eye_in_head.position = {side * half_ipd, 0.f, 0.f};
    // canted: each eye turned outwards by 10 deg about the head's +Y, its field of view turned back so that
    // both still see what an uncanted display shows (Pimax, Index, Reverb).
    const float cant = s->instance->config.canted ? -side * 0.17453293f : 0.f;
    eye_in_head.orientation = {0.f, std::sin(cant * 0.5f), 0.f, std::cos(cant * 0.5f)};
    const XrPosef eye = pose_mul(head, eye_in_head);
    views[i].pose = base_pose ? pose_mul(pose_inverse(*base_pose), eye) : pose_identity();
    // Wider towards the temple (54 deg) than the nose (45 deg), 50 deg up, 54 deg down.
    const float outer = 0.9424778f, inner = 0.7853982f;
    views[i].fov.angleLeft = (i == 0 ? -outer : -inner) + cant;
    views[i].fov.angleRight = (i == 0 ? inner : outer) + cant;
    views[i].fov.angleUp = 0.8726646f;
    views[i].fov.angleDown = -0.9424778f;
  });
}

}  // namespace

void add_space_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrEnumerateReferenceSpaces, enumerate_reference_spaces);
  PUSHPULL_XR_ADD(t, xrCreateReferenceSpace, create_reference_space);
  PUSHPULL_XR_ADD(t, xrGetReferenceSpaceBoundsRect, get_bounds);
  PUSHPULL_XR_ADD(t, xrCreateActionSpace, create_action_space);
  PUSHPULL_XR_ADD(t, xrLocateSpace, locate_space);
  PUSHPULL_XR_ADD(t, xrDestroySpace, destroy_space_entry);
  PUSHPULL_XR_ADD(t, xrLocateViews, locate_views);
}

}  // namespace pushpull::xrsim
