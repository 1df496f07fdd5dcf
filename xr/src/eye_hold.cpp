#include "eye_hold.hpp"

namespace pushpull::xr::detail {
namespace {

// v rotated by the unit quaternion q (q v q^-1), or by its inverse.
XrVector3f rotate(const XrQuaternionf& q, const XrVector3f& v, bool inverse = false) {
  const float s = inverse ? -1.0f : 1.0f;
  const float qx = s * q.x, qy = s * q.y, qz = s * q.z, qw = q.w;
  // t = 2 (q_xyz x v); v' = v + w t + q_xyz x t
  const float tx = 2.0f * (qy * v.z - qz * v.y), ty = 2.0f * (qz * v.x - qx * v.z),
              tz = 2.0f * (qx * v.y - qy * v.x);
  return {v.x + qw * tx + (qy * tz - qz * ty), v.y + qw * ty + (qz * tx - qx * tz),
          v.z + qw * tz + (qx * ty - qy * tx)};
}

}  // namespace

void EyeHold::apply(std::array<XrPosef, 2>& views, bool position_valid) {
  if (position_valid) {
    const XrVector3f &a = views[0].position, &b = views[1].position;
    head_centre_ = {0.5f * (a.x + b.x), 0.5f * (a.y + b.y), 0.5f * (a.z + b.z)};
    for (size_t i = 0; i < 2; ++i) {
      const XrVector3f& p = views[i].position;
      const XrVector3f offset{p.x - head_centre_.x, p.y - head_centre_.y, p.z - head_centre_.z};
      eye_offset_[i] = rotate(views[i].orientation, offset, /*inverse=*/true);
    }
    return;
  }
  for (size_t i = 0; i < 2; ++i) {
    const XrVector3f o = rotate(views[i].orientation, eye_offset_[i]);
    views[i].position = {head_centre_.x + o.x, head_centre_.y + o.y, head_centre_.z + o.z};
  }
}

}  // namespace pushpull::xr::detail
