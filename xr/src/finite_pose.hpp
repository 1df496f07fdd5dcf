// Private: whether a pose a runtime reported is usable: every component finite (a runtime's overflow or a
// driver's glitch gives inf or NaN, which would spread into the hit test, the solver's d and the recording).
// Pure; thread-safe.
#pragma once

#include <openxr/openxr.h>

#include <cmath>

namespace pushpull::xr::detail {

[[nodiscard]] inline bool finite_pose(const XrPosef& p) {
  return std::isfinite(p.position.x) && std::isfinite(p.position.y) && std::isfinite(p.position.z) &&
         std::isfinite(p.orientation.x) && std::isfinite(p.orientation.y) && std::isfinite(p.orientation.z) &&
         std::isfinite(p.orientation.w);
}

[[nodiscard]] inline bool finite_fov(const XrFovf& f) {
  return std::isfinite(f.angleLeft) && std::isfinite(f.angleRight) && std::isfinite(f.angleUp) &&
         std::isfinite(f.angleDown);
}

}  // namespace pushpull::xr::detail
