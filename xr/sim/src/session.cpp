// Sessions and their state machine:
//   create: IDLE -> READY;  xrBeginSession (READY) -> running;  first xrWaitFrame -> SYNCHRONIZED ->
//   VISIBLE -> FOCUSED;  exit (xrRequestExitSession or a scripted "exit") steps down to STOPPING;
//   xrEndSession (STOPPING) -> IDLE -> EXITING;  a scripted "loss" -> LOSS_PENDING.
#include "dispatch.hpp"
#include "input.hpp"
#include "sim_math.hpp"
#include "vulkan_util.hpp"

#include <cmath>

#include <algorithm>

namespace pushpull::xrsim {

XrResult get_session(XrSession handle, Session** out) {
  Session* s = lookup<Session>(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  *out = s;
  return XR_SUCCESS;
}

void begin_exit(Session& s, XrTime now) {
  s.exit_requested = true;
  if (s.state == XR_SESSION_STATE_FOCUSED) s.set_state(XR_SESSION_STATE_VISIBLE, now);
  if (s.state == XR_SESSION_STATE_VISIBLE) s.set_state(XR_SESSION_STATE_SYNCHRONIZED, now);
  if (s.state == XR_SESSION_STATE_SYNCHRONIZED || s.state == XR_SESSION_STATE_READY)
    s.set_state(XR_SESSION_STATE_STOPPING, now);
}

void run_script_events(Session& s, XrTime now) {
  if (!s.instance->script) return;
  const auto& events = s.instance->script->events();
  const double t = s.script_time(now) + InputScript::kTimeTolerance;
  while (s.next_script_event < events.size() && events[s.next_script_event].t <= t) {
    const ScriptEvent& e = events[s.next_script_event++];
    switch (e.kind) {
      case ScriptEventKind::exit:
        if (s.running && !s.exit_requested && !s.loss_pending) begin_exit(s, now);
        break;
      case ScriptEventKind::loss:
        if (!s.loss_pending) {
          s.loss_pending = true;
          if (s.instance->config.stays_lost) s.instance->headset_gone = true;
          s.set_state(XR_SESSION_STATE_LOSS_PENDING, now);
        }
        break;
      case ScriptEventKind::capture:
        s.capture_requested = true;
        break;
      case ScriptEventKind::failure:
        s.fail_next_begin = true;
        break;
      case ScriptEventKind::lost:
        s.lose_at_next_end = true;
        break;
      case ScriptEventKind::recenter:  // the reviewer recentred the view: STAGE and LOCAL are about to move
        for (const XrReferenceSpaceType type :
             {XR_REFERENCE_SPACE_TYPE_STAGE, XR_REFERENCE_SPACE_TYPE_LOCAL}) {
          XrEventDataBuffer buffer{};
          auto* change = reinterpret_cast<XrEventDataReferenceSpaceChangePending*>(&buffer);
          change->type = XR_TYPE_EVENT_DATA_REFERENCE_SPACE_CHANGE_PENDING;
          change->session = to_handle<XrSession>(&s);
          change->referenceSpaceType = type;
          change->changeTime = now;
          change->poseValid = XR_FALSE;
          change->poseInPreviousSpace.orientation.w = 1.0f;
          s.instance->push_event(buffer);
        }
        break;
    }
  }
}

void destroy_session(Session* s) {
  if (s->is_virtual_clock())
    s->instance->script_resume =
        Instance::ScriptResume{s->clock_origin, s->frames_waited, s->next_script_event};
  while (!s->spaces.empty()) destroy_space(s->spaces.back());
  while (!s->swapchains.empty()) destroy_swapchain(s->swapchains.back());
  for (ActionSet* set : s->attached) set->attached_to = nullptr;
  release_vulkan(s->vk);
  auto& list = s->instance->sessions;
  list.erase(std::remove(list.begin(), list.end(), s), list.end());
  // Drop queued events that name this session.
  auto& events = s->instance->events;
  const XrSession handle = to_handle<XrSession>(s);
  events.erase(
      std::remove_if(
          events.begin(), events.end(),
          [&](const XrEventDataBuffer& e) {
            if (e.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
              return reinterpret_cast<const XrEventDataSessionStateChanged&>(e).session == handle;
            if (e.type == XR_TYPE_EVENT_DATA_REFERENCE_SPACE_CHANGE_PENDING)
              return reinterpret_cast<const XrEventDataReferenceSpaceChangePending&>(e).session == handle;
            if (e.type == XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED)
              return reinterpret_cast<const XrEventDataInteractionProfileChanged&>(e).session == handle;
            return false;
          }),
      events.end());
  unregister_handle(s);
  delete s;
}

namespace {

XrResult XRAPI_CALL create_session(XrInstance handle, const XrSessionCreateInfo* info, XrSession* out) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_SESSION_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (info->createFlags != 0) return XR_ERROR_VALIDATION_FAILURE;
  auto session = std::make_unique<Session>();
  session->instance = instance;
  if (const XrResult r = bind_vulkan(*instance, info->next, &session->vk); XR_FAILED(r)) return r;
  // SteamVR's rule: the requirements call counts for one session.
  if (instance->config.requirements_per_session) instance->vk_requirements_queried = false;
  const XrTime now = monotonic_now();
  session->clock_origin = now;
  session->period = static_cast<XrDuration>(1e9 / instance->config.rate_hz);
  if (instance->script && instance->script_resume) {
    session->clock_origin = instance->script_resume->clock_origin;
    session->resume_frames = instance->script_resume->frames_waited;
    session->next_script_event = instance->script_resume->next_script_event;
  }
  // LOCAL: where the head starts, turned only about the vertical.
  const XrPosef head = head_pose(*session, now);
  const XrVector3f forward = quat_rotate(head.orientation, {0.f, 0.f, -1.f});
  const float yaw = std::atan2(-forward.x, -forward.z);
  session->local_origin = {{0.f, std::sin(yaw * 0.5f), 0.f, std::cos(yaw * 0.5f)}, head.position};
  Session* s = session.release();
  register_handle(s, HandleKind::session);
  instance->sessions.push_back(s);
  s->set_state(XR_SESSION_STATE_IDLE, now);
  s->set_state(XR_SESSION_STATE_READY, now);
  *out = to_handle<XrSession>(s);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_session_entry(XrSession handle) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  destroy_session(s);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL begin_session(XrSession handle, const XrSessionBeginInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_SESSION_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  const XrViewConfigurationType vc = info->primaryViewConfigurationType;
  if (vc != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
    const bool known =
        vc == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO || vc == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO;
    return known ? XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED : XR_ERROR_VALIDATION_FAILURE;
  }
  if (s->loss_pending) return XR_ERROR_SESSION_LOST;
  if (s->running) return XR_ERROR_SESSION_RUNNING;
  if (s->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  s->running = true;
  s->view_configuration = vc;
  s->frames_waited = s->resume_frames;  // 0, or where a lost session of this instance stopped
  s->frames_ended = s->resume_frames;   // so captures go on numbering the script's frames, never again from 0
  s->resume_frames = 0;
  s->last_display_time = 0;
  s->next_real_vsync = 0;
  s->waited_not_begun = false;
  s->frame_begun = false;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL end_session(XrSession handle) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (s->loss_pending) return XR_ERROR_SESSION_LOST;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (s->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
  s->running = false;
  s->waited_not_begun = false;
  s->frame_begun = false;
  s->frame_cv.notify_all();
  const XrTime now = s->input_time();
  s->set_state(XR_SESSION_STATE_IDLE, now);
  if (s->exit_requested)
    s->set_state(XR_SESSION_STATE_EXITING, now);
  else
    s->set_state(XR_SESSION_STATE_READY, now);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL request_exit_session(XrSession handle) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (s->loss_pending) return XR_ERROR_SESSION_LOST;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->instance->config.ignores_exit) begin_exit(*s, s->input_time());
  return XR_SUCCESS;
}

}  // namespace

void add_session_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrCreateSession, create_session);
  PUSHPULL_XR_ADD(t, xrDestroySession, destroy_session_entry);
  PUSHPULL_XR_ADD(t, xrBeginSession, begin_session);
  PUSHPULL_XR_ADD(t, xrEndSession, end_session);
  PUSHPULL_XR_ADD(t, xrRequestExitSession, request_exit_session);
}

}  // namespace pushpull::xrsim
