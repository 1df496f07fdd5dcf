// Private: whether a pose a runtime reported is usable: every component finite (a runtime's overflow or a
// driver's glitch gives inf or NaN, which would spread into the hit test, the solver's d and the recording).
// Pure; thread-safe.
#pragma once

#include <openxr/openxr.h>

#include <cmath>

namespace pushpull::xr::detail {

[[nodiscard]] inline bool finite_orientation(const XrQuaternionf& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

[[nodiscard]] inline bool finite_position(const XrVector3f& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

[[nodiscard]] inline bool finite_pose(const XrPosef& p) {
  return finite_orientation(p.orientation) && finite_position(p.position);
}

[[nodiscard]] inline bool finite_fov(const XrFovf& f) {
  return std::isfinite(f.angleLeft) && std::isfinite(f.angleRight) && std::isfinite(f.angleUp) &&
         std::isfinite(f.angleDown);
}

}  // namespace pushpull::xr::detail
