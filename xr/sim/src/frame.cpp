// Frame timing: xrWaitFrame / xrBeginFrame / xrEndFrame. xrWaitFrame blocks (without big_lock held)
// while a waited frame has not been begun, and paces at the configured rate on the real clock;
// with an input script the clock is virtual and it returns at once.
#include "compositor.hpp"
#include "dispatch.hpp"

#include <chrono>
#include <cmath>
#include <thread>

namespace pushpull::xrsim {
namespace {

XrResult XRAPI_CALL wait_frame(XrSession handle, const XrFrameWaitInfo* info, XrFrameState* state) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if ((info != nullptr && info->type != XR_TYPE_FRAME_WAIT_INFO) || state == nullptr ||
      state->type != XR_TYPE_FRAME_STATE)
    return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  s->frame_cv.wait(lock,
                   [&] { return !handle_is(s, HandleKind::session) || !s->waited_not_begun || !s->running; });
  if (!handle_is(s, HandleKind::session)) return XR_ERROR_HANDLE_INVALID;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  // Sleeps until `due` on the real clock with the lock released, holding the frame slot; false when the
  // session was destroyed meanwhile.
  auto sleep_until = [&](XrTime due, XrTime now) {
    s->waited_not_begun = true;
    lock.unlock();
    std::this_thread::sleep_for(std::chrono::nanoseconds(due - now));
    lock.lock();
    return handle_is(s, HandleKind::session);
  };
  XrTime display = 0;
  if (s->is_virtual_clock()) {
    // Frame n at exactly t0 + n / rate (rounded to the nanosecond), no drift from a rounded period.
    display = s->clock_origin + static_cast<XrTime>(std::llround(static_cast<double>(s->frames_waited) * 1e9 /
                                                                 s->instance->config.rate_hz));
    if (s->instance->config.pace) {  // the frame's moment on the real clock; late frames do not wait
      const XrTime now = monotonic_now();
      if (s->pace_origin == 0) s->pace_origin = now - (display - s->clock_origin);
      const XrTime due = s->pace_origin + (display - s->clock_origin);
      if (due > now && !sleep_until(due, now)) return XR_ERROR_HANDLE_INVALID;
    }
  } else {
    const XrTime now = monotonic_now();
    XrTime vsync = s->next_real_vsync == 0 ? now : s->next_real_vsync + s->period;
    if (vsync < now)  // the application fell behind: skip to the next vsync instead of catching up
      vsync += (now - vsync + s->period - 1) / s->period * s->period;
    s->next_real_vsync = vsync;
    if (!sleep_until(vsync, now)) return XR_ERROR_HANDLE_INVALID;
    display = vsync + s->period;
  }
  s->frames_waited++;
  s->waited_not_begun = true;
  s->last_display_time = display;
  if (s->state == XR_SESSION_STATE_READY && !s->exit_requested && !s->loss_pending) {
    s->set_state(XR_SESSION_STATE_SYNCHRONIZED, display);
    s->set_state(XR_SESSION_STATE_VISIBLE, display);
    s->set_state(XR_SESSION_STATE_FOCUSED, display);
  }
  run_script_events(*s, display);
  state->predictedDisplayTime = display;
  state->predictedDisplayPeriod = s->period;
  state->shouldRender =
      (s->state == XR_SESSION_STATE_VISIBLE || s->state == XR_SESSION_STATE_FOCUSED) ? XR_TRUE : XR_FALSE;
  return s->loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

XrResult XRAPI_CALL begin_frame(XrSession handle, const XrFrameBeginInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info != nullptr && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->waited_not_begun) return XR_ERROR_CALL_ORDER_INVALID;
  s->waited_not_begun = false;
  s->frame_cv.notify_all();
  if (s->fail_next_begin) {  // scripted: the runtime fails this frame (the app may go on or give up)
    s->fail_next_begin = false;
    return XR_ERROR_RUNTIME_FAILURE;
  }
  const bool discarded = s->frame_begun;
  s->frame_begun = true;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  return discarded ? XR_FRAME_DISCARDED : XR_SUCCESS;
}

XrResult XRAPI_CALL end_frame(XrSession handle, const XrFrameEndInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_FRAME_END_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->frame_begun) return XR_ERROR_CALL_ORDER_INVALID;
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  if (info->environmentBlendMode != s->instance->config.blend_mode) {
    const bool known = info->environmentBlendMode == XR_ENVIRONMENT_BLEND_MODE_OPAQUE ||
                       info->environmentBlendMode == XR_ENVIRONMENT_BLEND_MODE_ADDITIVE ||
                       info->environmentBlendMode == XR_ENVIRONMENT_BLEND_MODE_ALPHA_BLEND;
    return known ? XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED : XR_ERROR_VALIDATION_FAILURE;
  }
  if (const XrResult r = validate_layers(*s, *info); XR_FAILED(r)) return r;
  s->frame_begun = false;
  if (s->lose_at_next_end) {  // scripted: the session is lost in the middle of the app's frame
    s->lose_at_next_end = false;
    if (!s->loss_pending) {
      s->loss_pending = true;
      if (s->instance->config.stays_lost) s->instance->headset_gone = true;
      s->set_state(XR_SESSION_STATE_LOSS_PENDING, info->displayTime);
    }
    return XR_ERROR_SESSION_LOST;
  }
  if (s->instance->config.validation_noise && s->frames_ended == 0 && s->vk.device != VK_NULL_HANDLE) {
    // A zero-sized buffer (VUID-VkBufferCreateInfo-size-00912): the runtime's mistake, on the app's device.
    VkBufferCreateInfo create{};
    create.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    create.size = 0;
    create.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    create.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(s->vk.device, &create, nullptr, &buffer) == VK_SUCCESS && buffer != VK_NULL_HANDLE)
      vkDestroyBuffer(s->vk.device, buffer, nullptr);
  }
  capture_frame(*s, *info, s->frames_ended);
  s->frames_ended++;
  return s->loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

}  // namespace

void add_frame_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrWaitFrame, wait_frame);
  PUSHPULL_XR_ADD(t, xrBeginFrame, begin_frame);
  PUSHPULL_XR_ADD(t, xrEndFrame, end_frame);
}

}  // namespace pushpull::xrsim
