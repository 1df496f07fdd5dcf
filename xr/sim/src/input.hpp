// What the simulated devices report at a given time: the head and controller poses (T_stage_device)
// and input component values, from, in order of priority, XR_EXT_conformance_automation overrides,
// the input script, and defaults (head at 1.6 m looking down -Z, hands 20 cm either side of the
// body, 40 cm forward, 20 cm below the head; all values 0). Caller holds big_lock().
#pragma once

#include "state.hpp"

#include <optional>
#include <string>

namespace pushpull::xrsim {

// The user path a component path belongs to ("/user/hand/left" for ".../input/menu/click").
std::string top_level_path(const std::string& path);

XrPosef head_pose(const Session& session, XrTime time);
// The pose of a pose component (e.g. "/user/hand/right/input/aim/pose"); nullopt when its device is
// not tracked (made inactive through automation).
std::optional<XrPosef> device_pose(const Session& session, const std::string& component, XrTime time);
InputValue input_value(const Session& session, const std::string& component, XrTime time);

// T_stage_space at `time`; nullopt when the space cannot be located (inactive action space).
std::optional<XrPosef> space_in_stage(const Session& session, const Space& space, XrTime time);
// Whether space_in_stage's position is tracked (false: a guess, as a runtime reports a controller out of its
// cameras' view); reference spaces are.
bool space_position_tracked(const Session& session, const Space& space, XrTime time);

}  // namespace pushpull::xrsim
