// A hand as the push/pull interaction sees it (HandSample), from what OpenXR gives (an aim pose, floats) or
// from a mouse ray. The mouse ray goes through the same float pose a controller would give, so the desktop
// window and a replay of its recording on a simulated runtime feed the interaction bit-identical samples.
// Frames: stage space, metres; the aim ray is the pose's -Z axis, the controller's top its +Y.
// Thread-safety: pure functions.
#pragma once

#include "review_interaction.hpp"

#include "pushpull/xr/input.hpp"

#include <openxr/openxr.h>
#include <Eigen/Core>
#include <optional>

namespace pushpull::app {

// The sample of a controller: trigger, tracking and the aim ray of its aim pose.
[[nodiscard]] HandSample hand_sample(const xr::HandInput& in);

// A controller out of its tracking cameras' view is still located, by the runtime's guess (position valid,
// not tracked), which drifts; its orientation still comes from its own gyroscopes. The sample of `in` with
// the ray's origin of `last_tracked` while its position is such a guess (the direction and the trigger as
// read), not tracked at all before any tracked pose; `last_tracked` keeps the latest tracked sample. A drag
// thus holds where the hand was last seen and never pushes the guess into the model, and the ray still turns
// with the hand.
[[nodiscard]] HandSample hold_untracked(const xr::HandInput& in, std::optional<HandSample>& last_tracked);

// The aim pose (float, as OpenXR holds it) of a ray: position = origin, orientation = the shortest rotation
// taking -Z to `direction` (need not be unit; not zero).
[[nodiscard]] XrPosef pointer_pose(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

}  // namespace pushpull::app
