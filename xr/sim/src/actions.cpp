// Action sets, actions, suggested bindings, attaching, the current interaction profile, xrSyncActions,
// action states, bound sources and their names, haptics (recorded in Session::haptics).
#include "dispatch.hpp"
#include "input.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace pushpull::xrsim {

void destroy_action_set(ActionSet* set) {
  for (Action* a : set->actions) {
    // Action spaces keep working on a destroyed action in the spec; here they stop locating.
    for (Session* s : set->instance->sessions)
      for (Space* space : s->spaces)
        if (space->action == a) space->action = nullptr;
    for (auto& [profile, bindings] : set->instance->suggested)
      bindings.erase(
          std::remove_if(bindings.begin(), bindings.end(), [&](const auto& b) { return b.first == a; }),
          bindings.end());
    unregister_handle(a);
    delete a;
  }
  auto& list = set->instance->action_sets;
  list.erase(std::remove(list.begin(), list.end(), set), list.end());
  for (Session* s : set->instance->sessions)
    s->attached.erase(std::remove(s->attached.begin(), s->attached.end(), set), s->attached.end());
  unregister_handle(set);
  delete set;
}

namespace {

bool well_formed_name(const char* name, std::size_t size) {
  const std::size_t n = strnlen(name, size);
  if (n == 0 || n == size) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const char c = name[i];
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.')) return false;
  }
  return true;
}

bool is_top_level_user_path(const std::string& p) {
  return p == "/user/hand/left" || p == "/user/hand/right" || p == "/user/head" || p == "/user/gamepad" ||
         p == "/user/treadmill";
}

ComponentKind kind_of(XrActionType t) {
  switch (t) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
      return ComponentKind::boolean;
    case XR_ACTION_TYPE_FLOAT_INPUT:
      return ComponentKind::scalar;
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
      return ComponentKind::vector2;
    case XR_ACTION_TYPE_POSE_INPUT:
      return ComponentKind::pose;
    default:
      return ComponentKind::haptic;
  }
}

bool compatible(XrActionType t, ComponentKind k) {
  switch (t) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
    case XR_ACTION_TYPE_FLOAT_INPUT:
      return k == ComponentKind::boolean || k == ComponentKind::scalar;
    default:
      return k == kind_of(t);
  }
}

XrResult XRAPI_CALL create_action_set(XrInstance handle, const XrActionSetCreateInfo* info,
                                      XrActionSet* out) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_ACTION_SET_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (!well_formed_name(info->actionSetName, XR_MAX_ACTION_SET_NAME_SIZE)) return XR_ERROR_NAME_INVALID;
  if (strnlen(info->localizedActionSetName, XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE) == 0)
    return XR_ERROR_LOCALIZED_NAME_INVALID;
  for (const ActionSet* other : instance->action_sets) {
    if (other->name == info->actionSetName) return XR_ERROR_NAME_DUPLICATED;
    if (other->localized_name == info->localizedActionSetName) return XR_ERROR_LOCALIZED_NAME_DUPLICATED;
  }
  auto* set = new ActionSet;
  set->instance = instance;
  set->name = info->actionSetName;
  set->localized_name = info->localizedActionSetName;
  set->priority = info->priority;
  register_handle(set, HandleKind::action_set);
  instance->action_sets.push_back(set);
  *out = to_handle<XrActionSet>(set);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_action_set_entry(XrActionSet handle) {
  Lock lock(big_lock());
  ActionSet* set = lookup<ActionSet>(handle);
  if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
  destroy_action_set(set);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL create_action(XrActionSet handle, const XrActionCreateInfo* info, XrAction* out) {
  Lock lock(big_lock());
  ActionSet* set = lookup<ActionSet>(handle);
  if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_ACTION_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (set->attached_to != nullptr) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  if (!well_formed_name(info->actionName, XR_MAX_ACTION_NAME_SIZE)) return XR_ERROR_NAME_INVALID;
  if (strnlen(info->localizedActionName, XR_MAX_LOCALIZED_ACTION_NAME_SIZE) == 0)
    return XR_ERROR_LOCALIZED_NAME_INVALID;
  switch (info->actionType) {
    case XR_ACTION_TYPE_BOOLEAN_INPUT:
    case XR_ACTION_TYPE_FLOAT_INPUT:
    case XR_ACTION_TYPE_VECTOR2F_INPUT:
    case XR_ACTION_TYPE_POSE_INPUT:
    case XR_ACTION_TYPE_VIBRATION_OUTPUT:
      break;
    default:
      return XR_ERROR_VALIDATION_FAILURE;
  }
  if (info->countSubactionPaths > 0 && info->subactionPaths == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  std::vector<XrPath> subactions;
  for (uint32_t i = 0; i < info->countSubactionPaths; ++i) {
    const std::string* p = set->instance->path_string(info->subactionPaths[i]);
    if (p == nullptr) return XR_ERROR_PATH_INVALID;
    if (!is_top_level_user_path(*p)) return XR_ERROR_PATH_UNSUPPORTED;
    if (std::find(subactions.begin(), subactions.end(), info->subactionPaths[i]) != subactions.end())
      return XR_ERROR_PATH_UNSUPPORTED;
    subactions.push_back(info->subactionPaths[i]);
  }
  for (const Action* other : set->actions) {
    if (other->name == info->actionName) return XR_ERROR_NAME_DUPLICATED;
    if (other->localized_name == info->localizedActionName) return XR_ERROR_LOCALIZED_NAME_DUPLICATED;
  }
  auto* action = new Action;
  action->set = set;
  action->name = info->actionName;
  action->localized_name = info->localizedActionName;
  action->type = info->actionType;
  action->subactions = subactions;
  register_handle(action, HandleKind::action);
  set->actions.push_back(action);
  *out = to_handle<XrAction>(action);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_action(XrAction handle) {
  Lock lock(big_lock());
  Action* action = lookup<Action>(handle);
  if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
  auto& list = action->set->actions;
  list.erase(std::remove(list.begin(), list.end(), action), list.end());
  for (auto& [profile, bindings] : action->set->instance->suggested)
    bindings.erase(
        std::remove_if(bindings.begin(), bindings.end(), [&](const auto& b) { return b.first == action; }),
        bindings.end());
  for (Session* s : action->set->instance->sessions)
    for (Space* space : s->spaces)
      if (space->action == action) space->action = nullptr;
  unregister_handle(action);
  delete action;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL suggest_bindings(XrInstance handle, const XrInteractionProfileSuggestedBinding* info) {
  Lock lock(big_lock());
  Instance* instance = lookup<Instance>(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING ||
      info->countSuggestedBindings == 0 || info->suggestedBindings == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  const std::string* profile_path = instance->path_string(info->interactionProfile);
  if (profile_path == nullptr) return XR_ERROR_PATH_INVALID;
  const InteractionProfile* profile = find_profile(*profile_path);
  if (profile == nullptr) return XR_ERROR_PATH_UNSUPPORTED;
  // A profile an extension brings exists only with that extension enabled (the spec's rule for
  // extension-defined interaction profile paths).
  if (!profile->extension.empty() && instance->extensions.count(profile->extension) == 0)
    return XR_ERROR_PATH_UNSUPPORTED;
  std::vector<std::pair<Action*, std::string>> bindings;
  for (uint32_t i = 0; i < info->countSuggestedBindings; ++i) {
    Action* action = lookup<Action>(info->suggestedBindings[i].action);
    if (action == nullptr || action->set->instance != instance) return XR_ERROR_HANDLE_INVALID;
    if (action->set->attached_to != nullptr) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    const std::string* binding = instance->path_string(info->suggestedBindings[i].binding);
    if (binding == nullptr) return XR_ERROR_PATH_INVALID;
    const ProfileComponent* c = resolve_binding(*profile, *binding, kind_of(action->type));
    if (c == nullptr || !compatible(action->type, c->kind)) return XR_ERROR_PATH_UNSUPPORTED;
    bindings.emplace_back(action, c->path);
  }
  for (const ActionSet* set : instance->action_sets)
    if (set->attached_to != nullptr) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  instance->suggested[*profile_path] = std::move(bindings);  // a new suggestion replaces the previous one
  return XR_SUCCESS;
}

}  // namespace

void choose_interaction_profile(Session& s) {
  Instance& instance = *s.instance;
  const auto has_bindings = [&](const std::string& path) {
    const auto it = instance.suggested.find(path);
    if (it == instance.suggested.end()) return false;
    for (const auto& [action, component] : it->second)
      if (std::find(s.attached.begin(), s.attached.end(), action->set) != s.attached.end()) return true;
    return false;
  };
  s.profile = nullptr;
  const bool none = instance.config.profile == "none";  // no controller on (hand tracking only, or off)
  if (!instance.config.profile.empty() && has_bindings(instance.config.profile))
    s.profile = find_profile(instance.config.profile);
  for (const InteractionProfile& p : interaction_profiles())
    if (s.profile == nullptr && has_bindings(p.path) && !none) s.profile = &p;
  // A profile asked for that cannot be current (unknown here, or the application suggested no bindings for
  // it): said, since the script's paths for it then read nothing.
  if (!instance.config.profile.empty() && !none &&
      (s.profile == nullptr || instance.config.profile != s.profile->path))
    std::fprintf(stderr,
                 "pushpull xr/sim: PUSHPULL_XR_SIM_PROFILE=%s is not a profile the application suggested "
                 "bindings for (or xr/sim knows); the controllers are %s\n",
                 instance.config.profile.c_str(), s.profile != nullptr ? s.profile->path.c_str() : "unbound");
  for (ActionSet* set : s.attached)
    for (Action* a : set->actions) {
      a->bound.clear();
      a->states.clear();
      a->states[XR_NULL_PATH] = {};
      for (XrPath sub : a->subactions) a->states[sub] = {};
    }
  if (s.profile == nullptr) return;
  for (const auto& [action, component] : instance.suggested[s.profile->path])
    if (std::find(s.attached.begin(), s.attached.end(), action->set) != s.attached.end() &&
        std::find(action->bound.begin(), action->bound.end(), component) == action->bound.end())
      action->bound.push_back(component);
  XrEventDataBuffer buffer{};
  auto* e = reinterpret_cast<XrEventDataInteractionProfileChanged*>(&buffer);
  e->type = XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
  e->session = to_handle<XrSession>(&s);
  instance.push_event(buffer);
}

namespace {

XrResult XRAPI_CALL attach_action_sets(XrSession handle, const XrSessionActionSetsAttachInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO ||
      info->countActionSets == 0 || info->actionSets == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  if (!s->attached.empty()) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  std::vector<ActionSet*> sets;
  for (uint32_t i = 0; i < info->countActionSets; ++i) {
    ActionSet* set = lookup<ActionSet>(info->actionSets[i]);
    if (set == nullptr || set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (std::find(sets.begin(), sets.end(), set) == sets.end()) sets.push_back(set);
  }
  for (ActionSet* set : sets) set->attached_to = s;
  s->attached = sets;
  choose_interaction_profile(*s);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_current_profile(XrSession handle, XrPath top_level,
                                        XrInteractionProfileState* state) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (state == nullptr || state->type != XR_TYPE_INTERACTION_PROFILE_STATE)
    return XR_ERROR_VALIDATION_FAILURE;
  const std::string* path = s->instance->path_string(top_level);
  if (path == nullptr) return XR_ERROR_PATH_INVALID;
  if (!is_top_level_user_path(*path)) return XR_ERROR_PATH_UNSUPPORTED;
  if (s->attached.empty()) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  const bool hand = *path == "/user/hand/left" || *path == "/user/hand/right";
  state->interactionProfile = (hand && s->profile != nullptr && s->inactive_devices.count(*path) == 0)
                                  ? s->instance->intern(s->profile->path)
                                  : XR_NULL_PATH;
  return XR_SUCCESS;
}

// Checks action + subaction path of a get-state / haptic call.
XrResult check_action(Session& s, XrAction handle, XrPath subaction, Action** out) {
  Action* a = lookup<Action>(handle);
  if (a == nullptr || a->set->instance != s.instance) return XR_ERROR_HANDLE_INVALID;
  if (a->set->attached_to != &s) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  if (subaction != XR_NULL_PATH) {
    if (s.instance->path_string(subaction) == nullptr) return XR_ERROR_PATH_INVALID;
    if (std::find(a->subactions.begin(), a->subactions.end(), subaction) == a->subactions.end())
      return XR_ERROR_PATH_UNSUPPORTED;
  }
  *out = a;
  return XR_SUCCESS;
}

template <class State>
XrResult get_state(XrSession handle, const XrActionStateGetInfo* info, State* state,
                   XrStructureType state_type, XrActionType action_type, Action** action_out,
                   const ActionState** out) {
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || state == nullptr || info->type != XR_TYPE_ACTION_STATE_GET_INFO ||
      state->type != state_type)
    return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_action(*s, info->action, info->subactionPath, action_out); XR_FAILED(r))
    return r;
  if ((*action_out)->type != action_type) return XR_ERROR_ACTION_TYPE_MISMATCH;
  static const ActionState inactive{};
  const auto it = (*action_out)->states.find(info->subactionPath);
  *out = it != (*action_out)->states.end() ? &it->second : &inactive;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_boolean(XrSession h, const XrActionStateGetInfo* info, XrActionStateBoolean* state) {
  Lock lock(big_lock());
  Action* a = nullptr;
  const ActionState* st = nullptr;
  const XrResult r =
      get_state(h, info, state, XR_TYPE_ACTION_STATE_BOOLEAN, XR_ACTION_TYPE_BOOLEAN_INPUT, &a, &st);
  if (XR_FAILED(r)) return r;
  state->currentState = st->x > 0.5f ? XR_TRUE : XR_FALSE;
  state->changedSinceLastSync = st->changed ? XR_TRUE : XR_FALSE;
  state->lastChangeTime = st->last_change;
  state->isActive = st->active ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_float(XrSession h, const XrActionStateGetInfo* info, XrActionStateFloat* state) {
  Lock lock(big_lock());
  Action* a = nullptr;
  const ActionState* st = nullptr;
  const XrResult r =
      get_state(h, info, state, XR_TYPE_ACTION_STATE_FLOAT, XR_ACTION_TYPE_FLOAT_INPUT, &a, &st);
  if (XR_FAILED(r)) return r;
  state->currentState = st->x;
  state->changedSinceLastSync = st->changed ? XR_TRUE : XR_FALSE;
  state->lastChangeTime = st->last_change;
  state->isActive = st->active ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_vector2(XrSession h, const XrActionStateGetInfo* info, XrActionStateVector2f* state) {
  Lock lock(big_lock());
  Action* a = nullptr;
  const ActionState* st = nullptr;
  const XrResult r =
      get_state(h, info, state, XR_TYPE_ACTION_STATE_VECTOR2F, XR_ACTION_TYPE_VECTOR2F_INPUT, &a, &st);
  if (XR_FAILED(r)) return r;
  state->currentState = {st->x, st->y};
  state->changedSinceLastSync = st->changed ? XR_TRUE : XR_FALSE;
  state->lastChangeTime = st->last_change;
  state->isActive = st->active ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL get_pose(XrSession h, const XrActionStateGetInfo* info, XrActionStatePose* state) {
  Lock lock(big_lock());
  Action* a = nullptr;
  const ActionState* st = nullptr;
  const XrResult r = get_state(h, info, state, XR_TYPE_ACTION_STATE_POSE, XR_ACTION_TYPE_POSE_INPUT, &a, &st);
  if (XR_FAILED(r)) return r;
  state->isActive = st->active ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

// The combined value of an action over the components bound under `subaction` (all when empty).
ActionState evaluate(const Session& s, const Action& a, const std::string& subaction, XrTime time) {
  ActionState out;
  for (const std::string& c : a.bound) {
    const std::string user = top_level_path(c);
    if (!subaction.empty() && user != subaction) continue;
    if (s.inactive_devices.count(user) != 0) continue;
    out.active = true;
    if (a.type == XR_ACTION_TYPE_POSE_INPUT || a.type == XR_ACTION_TYPE_VIBRATION_OUTPUT) continue;
    const InputValue v = input_value(s, c, time);
    switch (a.type) {
      case XR_ACTION_TYPE_BOOLEAN_INPUT:
        out.x = std::max(out.x, v.x > 0.5f ? 1.f : 0.f);
        break;
      case XR_ACTION_TYPE_FLOAT_INPUT:
        if (std::fabs(v.x) > std::fabs(out.x)) out.x = v.x;
        break;
      case XR_ACTION_TYPE_VECTOR2F_INPUT:
        if (v.x * v.x + v.y * v.y > out.x * out.x + out.y * out.y) out.x = v.x, out.y = v.y;
        break;
      default:
        break;
    }
  }
  return out;
}

XrResult XRAPI_CALL sync_actions(XrSession handle, const XrActionsSyncInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_ACTIONS_SYNC_INFO ||
      (info->countActiveActionSets > 0 && info->activeActionSets == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;
  // Which (set, subaction) pairs are active.
  std::vector<std::pair<const ActionSet*, XrPath>> active;
  for (uint32_t i = 0; i < info->countActiveActionSets; ++i) {
    const ActionSet* set = lookup<ActionSet>(info->activeActionSets[i].actionSet);
    if (set == nullptr || set->instance != s->instance) return XR_ERROR_HANDLE_INVALID;
    if (set->attached_to != s) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    const XrPath sub = info->activeActionSets[i].subactionPath;
    if (sub != XR_NULL_PATH) {
      const std::string* p = s->instance->path_string(sub);
      if (p == nullptr) return XR_ERROR_PATH_INVALID;
      if (!is_top_level_user_path(*p)) return XR_ERROR_PATH_UNSUPPORTED;
    }
    active.emplace_back(set, sub);
  }
  if (s->attached.empty()) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  const bool focused = s->state == XR_SESSION_STATE_FOCUSED;
  const XrTime now = s->input_time();
  run_script_events(*s, now);
  for (ActionSet* set : s->attached) {
    for (Action* a : set->actions) {
      for (auto& [sub, state] : a->states) {
        const std::string sub_name = sub == XR_NULL_PATH ? std::string() : *s->instance->path_string(sub);
        bool set_active = false;
        for (const auto& [aset, asub] : active)
          set_active =
              set_active || (aset == set && (asub == XR_NULL_PATH || sub == XR_NULL_PATH || asub == sub));
        ActionState next = (focused && set_active) ? evaluate(*s, *a, sub_name, now) : ActionState{};
        if (!next.active) next.x = next.y = 0.f;
        next.changed = next.active && (next.x != state.x || next.y != state.y);  // inactive reads as 0
        next.last_change = next.changed || (next.active && !state.active) ? now : state.last_change;
        state = next;
      }
    }
  }
  return focused ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

XrResult XRAPI_CALL enumerate_bound_sources(XrSession handle,
                                            const XrBoundSourcesForActionEnumerateInfo* info,
                                            uint32_t capacity, uint32_t* count, XrPath* sources) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO ||
      (capacity != 0 && sources == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;
  Action* a = nullptr;
  if (const XrResult r = check_action(*s, info->action, XR_NULL_PATH, &a); XR_FAILED(r)) return r;
  const std::vector<std::string> bound = a->bound;
  return two_call(capacity, count, static_cast<uint32_t>(bound.size()),
                  [&](uint32_t i) { sources[i] = s->instance->intern(bound[i]); });
}

XrResult XRAPI_CALL get_localized_name(XrSession handle, const XrInputSourceLocalizedNameGetInfo* info,
                                       uint32_t capacity, uint32_t* count, char* buffer) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO ||
      info->whichComponents == 0)
    return XR_ERROR_VALIDATION_FAILURE;
  const std::string* source = s->instance->path_string(info->sourcePath);
  if (source == nullptr) return XR_ERROR_PATH_INVALID;
  if (s->attached.empty()) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  const std::string user = top_level_path(*source);
  if (user.empty()) return XR_ERROR_PATH_UNSUPPORTED;
  std::string name;
  const auto append = [&](const std::string& part) {
    if (part.empty()) return;
    if (!name.empty()) name += ' ';
    name += part;
  };
  if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT) append(localized_user_path(user));
  if ((info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT) &&
      s->profile != nullptr)
    append(s->profile->localized_name);
  if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT)
    append(localized_component(*source));
  return two_call_string(name, capacity, count, buffer);
}

XrResult haptic_common(XrSession handle, const XrHapticActionInfo* info, Session** s_out, Action** a_out) {
  if (const XrResult r = get_session(handle, s_out); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_HAPTIC_ACTION_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (const XrResult r = check_action(**s_out, info->action, info->subactionPath, a_out); XR_FAILED(r))
    return r;
  if ((*a_out)->type != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  return XR_SUCCESS;
}

void record_haptic(Session& s, const Action& a, XrPath subaction, const XrHapticVibration* v) {
  const std::string sub = subaction == XR_NULL_PATH ? std::string() : *s.instance->path_string(subaction);
  const auto it = a.states.find(subaction);
  if (s.state != XR_SESSION_STATE_FOCUSED || it == a.states.end() || !it->second.active) return;
  const XrTime now = s.input_time();
  for (const std::string& c : a.bound) {
    if (!sub.empty() && top_level_path(c) != sub) continue;
    const HapticRecord r{now,         c, v ? v->duration : 0, v ? v->frequency : 0.f, v ? v->amplitude : 0.f,
                         v == nullptr};
    s.haptics.push_back(r);
    const std::string& log = s.instance->config.haptics_log;
    if (log.empty()) continue;
    nlohmann::json j{{"t", s.script_time(now)}, {"path", c}};
    if (r.stop) {
      j["stop"] = true;
    } else {
      j["duration_ns"] = r.duration;
      j["frequency"] = r.frequency;
      j["amplitude"] = r.amplitude;
    }
    std::ofstream(log, std::ios::app) << j.dump() << "\n";
  }
}

XrResult XRAPI_CALL apply_haptic(XrSession handle, const XrHapticActionInfo* info,
                                 const XrHapticBaseHeader* haptic) {
  Lock lock(big_lock());
  Session* s = nullptr;
  Action* a = nullptr;
  if (const XrResult r = haptic_common(handle, info, &s, &a); XR_FAILED(r)) return r;
  if (haptic == nullptr || haptic->type != XR_TYPE_HAPTIC_VIBRATION) return XR_ERROR_VALIDATION_FAILURE;
  if (s->instance->config.haptics_fail) return XR_ERROR_RUNTIME_FAILURE;
  record_haptic(*s, *a, info->subactionPath, reinterpret_cast<const XrHapticVibration*>(haptic));
  return s->state == XR_SESSION_STATE_FOCUSED ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

XrResult XRAPI_CALL stop_haptic(XrSession handle, const XrHapticActionInfo* info) {
  Lock lock(big_lock());
  Session* s = nullptr;
  Action* a = nullptr;
  if (const XrResult r = haptic_common(handle, info, &s, &a); XR_FAILED(r)) return r;
  record_haptic(*s, *a, info->subactionPath, nullptr);
  return s->state == XR_SESSION_STATE_FOCUSED ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

}  // namespace

void add_action_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrCreateActionSet, create_action_set);
  PUSHPULL_XR_ADD(t, xrDestroyActionSet, destroy_action_set_entry);
  PUSHPULL_XR_ADD(t, xrCreateAction, create_action);
  PUSHPULL_XR_ADD(t, xrDestroyAction, destroy_action);
  PUSHPULL_XR_ADD(t, xrSuggestInteractionProfileBindings, suggest_bindings);
  PUSHPULL_XR_ADD(t, xrAttachSessionActionSets, attach_action_sets);
  PUSHPULL_XR_ADD(t, xrGetCurrentInteractionProfile, get_current_profile);
  PUSHPULL_XR_ADD(t, xrGetActionStateBoolean, get_boolean);
  PUSHPULL_XR_ADD(t, xrGetActionStateFloat, get_float);
  PUSHPULL_XR_ADD(t, xrGetActionStateVector2f, get_vector2);
  PUSHPULL_XR_ADD(t, xrGetActionStatePose, get_pose);
  PUSHPULL_XR_ADD(t, xrSyncActions, sync_actions);
  PUSHPULL_XR_ADD(t, xrEnumerateBoundSourcesForAction, enumerate_bound_sources);
  PUSHPULL_XR_ADD(t, xrGetInputSourceLocalizedName, get_localized_name);
  PUSHPULL_XR_ADD(t, xrApplyHapticFeedback, apply_haptic);
  PUSHPULL_XR_ADD(t, xrStopHapticFeedback, stop_haptic);
}

}  // namespace pushpull::xrsim
