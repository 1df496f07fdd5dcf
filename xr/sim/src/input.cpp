#include "input.hpp"

#include "sim_math.hpp"

#include <cmath>

namespace pushpull::xrsim {

std::string top_level_path(const std::string& path) {
  for (const char* u : {"/user/hand/left", "/user/hand/right", "/user/head", "/user/gamepad"}) {
    const std::string p(u);
    if (path == p || (path.compare(0, p.size(), p) == 0 && path.size() > p.size() && path[p.size()] == '/'))
      return p;
  }
  return {};
}

XrPosef head_pose(const Session& s, XrTime time) {
  if (const auto it = s.location_overrides.find("/user/head"); it != s.location_overrides.end())
    return it->second.second;
  if (s.instance->script)
    if (const auto p = s.instance->script->pose_at("/user/head", s.script_time(time))) return *p;
  XrPosef head = pose_identity();
  head.position = {0.f, 1.6f, 0.f};
  return head;
}

namespace {

// A script that moves only the aim (or only the grip) moves the whole controller: the other pose of
// `component`'s controller.
std::string other_pose(const std::string& component) {
  const bool aim = component.size() > 9 && component.compare(component.size() - 9, 9, "/aim/pose") == 0;
  return top_level_path(component) + (aim ? "/input/grip/pose" : "/input/aim/pose");
}

// The components bound to an action space's action on its subaction path (all of them without one).
template <class Visit>
void for_each_bound(const Session& s, const Space& space, Visit visit) {
  for (const std::string& bound : space.action->bound) {
    if (space.subaction != XR_NULL_PATH) {
      const std::string* sub = s.instance->path_string(space.subaction);
      if (sub == nullptr || top_level_path(bound) != *sub) continue;
    }
    if (visit(bound)) return;
  }
}

}  // namespace

std::optional<XrPosef> device_pose(const Session& s, const std::string& component, XrTime time) {
  const std::string user = top_level_path(component);
  if (s.inactive_devices.count(user) != 0) return std::nullopt;
  if (user == "/user/head") return head_pose(s, time);
  if (const auto it = s.location_overrides.find(component); it != s.location_overrides.end())
    return it->second.second;
  if (s.instance->script) {
    const double t = s.script_time(time);
    if (const auto p = s.instance->script->pose_at(component, t)) return *p;
    if (const auto p = s.instance->script->pose_at(other_pose(component), t)) return *p;
  }
  XrPosef hand = pose_identity();
  const float side = user == "/user/hand/left" ? -1.f : 1.f;
  hand.position = {0.2f * side, 1.4f, -0.4f};
  return hand;
}

InputValue input_value(const Session& s, const std::string& component, XrTime time) {
  if (s.inactive_devices.count(top_level_path(component)) != 0) return {};
  if (const auto it = s.overrides.find(component); it != s.overrides.end()) return it->second;
  if (s.instance->script)
    if (const auto v = s.instance->script->value_at(component, s.script_time(time))) return *v;
  return {};
}

std::optional<XrPosef> space_in_stage(const Session& s, const Space& space, XrTime time) {
  if (!space.is_action_space) {
    switch (space.reference) {
      case XR_REFERENCE_SPACE_TYPE_STAGE: {
        XrPosef origin = pose_identity();
        origin.position.y = s.instance->config.stage_height_m;
        return pose_mul(origin, space.offset);
      }
      case XR_REFERENCE_SPACE_TYPE_LOCAL:
        return pose_mul(s.local_origin, space.offset);
      case XR_REFERENCE_SPACE_TYPE_VIEW:
        return pose_mul(head_pose(s, time), space.offset);
      default:
        return std::nullopt;
    }
  }
  const Action* action = space.action;
  if (action == nullptr) return std::nullopt;  // its action was destroyed
  const auto state = action->states.find(space.subaction);
  if (state == action->states.end() || !state->second.active) return std::nullopt;
  std::optional<XrPosef> pose;
  for_each_bound(s, space, [&](const std::string& bound) {
    if (const auto p = device_pose(s, bound, time)) pose = pose_mul(*p, space.offset);
    return pose.has_value();
  });
  return pose;
}

bool space_position_tracked(const Session& s, const Space& space, XrTime time) {
  if (!space.is_action_space || space.action == nullptr || !s.instance->script) return true;
  const double t = s.script_time(time);
  std::optional<bool> tracked;
  for_each_bound(s, space, [&](const std::string& bound) {
    tracked = s.instance->script->tracked_at(bound, t);
    if (!tracked) tracked = s.instance->script->tracked_at(other_pose(bound), t);
    return tracked.has_value();
  });
  return tracked.value_or(true);
}

}  // namespace pushpull::xrsim
