#include "eye_hold.hpp"

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace pushpull::xr::detail {
namespace {

glm::quat to_glm(const XrQuaternionf& q) {
  return glm::quat(q.w, q.x, q.y, q.z);
}
glm::vec3 to_glm(const XrVector3f& v) {
  return {v.x, v.y, v.z};
}
XrVector3f to_xr(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

void EyeHold::apply(std::array<XrPosef, 2>& views, bool position_valid) {
  if (position_valid) {
    const glm::vec3 centre = 0.5f * (to_glm(views[0].position) + to_glm(views[1].position));
    head_centre_ = to_xr(centre);
    for (size_t i = 0; i < 2; ++i)
      eye_offset_[i] =
          to_xr(glm::conjugate(to_glm(views[i].orientation)) * (to_glm(views[i].position) - centre));
    return;
  }
  for (size_t i = 0; i < 2; ++i)
    views[i].position = to_xr(to_glm(head_centre_) + to_glm(views[i].orientation) * to_glm(eye_offset_[i]));
}

}  // namespace pushpull::xr::detail
