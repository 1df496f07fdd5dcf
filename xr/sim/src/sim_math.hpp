// Small rigid-transform helpers on OpenXR's own types. Poses are T_base_child: a pose p maps
// coordinates in the child frame to the base frame (x_base = p.orientation * x_child + p.position).
// Quaternions are unit (x, y, z, w). Pure functions, thread-safe.
#pragma once

#include <openxr/openxr.h>

#include <cmath>

namespace pushpull::xrsim {

inline XrQuaternionf quat_identity() {
  return {0.f, 0.f, 0.f, 1.f};
}
inline XrPosef pose_identity() {
  return {quat_identity(), {0.f, 0.f, 0.f}};
}

inline XrQuaternionf quat_mul(const XrQuaternionf& a, const XrQuaternionf& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
inline XrQuaternionf quat_conj(const XrQuaternionf& q) {
  return {-q.x, -q.y, -q.z, q.w};
}

inline XrVector3f quat_rotate(const XrQuaternionf& q, const XrVector3f& v) {
  const XrQuaternionf p{v.x, v.y, v.z, 0.f};
  const XrQuaternionf r = quat_mul(quat_mul(q, p), quat_conj(q));
  return {r.x, r.y, r.z};
}

inline XrQuaternionf quat_normalize(const XrQuaternionf& q) {
  const float n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (n <= 0.f) return quat_identity();
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

// True when |q| is 1 within the tolerance the OpenXR spec allows (1%).
inline bool quat_is_unit(const XrQuaternionf& q) {
  const float n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return std::fabs(n - 1.f) <= 0.01f;
}

// a * b: T_a_c = T_a_b * T_b_c.
inline XrPosef pose_mul(const XrPosef& a, const XrPosef& b) {
  XrPosef r;
  r.orientation = quat_mul(a.orientation, b.orientation);
  const XrVector3f t = quat_rotate(a.orientation, b.position);
  r.position = {t.x + a.position.x, t.y + a.position.y, t.z + a.position.z};
  return r;
}

inline XrPosef pose_inverse(const XrPosef& p) {
  XrPosef r;
  r.orientation = quat_conj(p.orientation);
  const XrVector3f t = quat_rotate(r.orientation, p.position);
  r.position = {-t.x, -t.y, -t.z};
  return r;
}

// Normalized linear interpolation of positions and slerp of orientations, s in [0, 1].
inline XrPosef pose_lerp(const XrPosef& a, const XrPosef& b, double s) {
  XrPosef r;
  const float f = static_cast<float>(s);
  r.position = {a.position.x + (b.position.x - a.position.x) * f,
                a.position.y + (b.position.y - a.position.y) * f,
                a.position.z + (b.position.z - a.position.z) * f};
  XrQuaternionf qb = b.orientation;
  double dot =
      a.orientation.x * qb.x + a.orientation.y * qb.y + a.orientation.z * qb.z + a.orientation.w * qb.w;
  if (dot < 0) {
    qb = {-qb.x, -qb.y, -qb.z, -qb.w};
    dot = -dot;
  }
  double wa = 1.0 - s, wb = s;
  if (dot < 0.9995) {
    const double theta = std::acos(dot);
    wa = std::sin((1.0 - s) * theta) / std::sin(theta);
    wb = std::sin(s * theta) / std::sin(theta);
  }
  const XrQuaternionf& qa = a.orientation;
  r.orientation =
      quat_normalize({static_cast<float>(wa * qa.x + wb * qb.x), static_cast<float>(wa * qa.y + wb * qb.y),
                      static_cast<float>(wa * qa.z + wb * qb.z), static_cast<float>(wa * qa.w + wb * qb.w)});
  return r;
}

}  // namespace pushpull::xrsim
