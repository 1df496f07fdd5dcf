#include "pushpull/renderer/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pushpull::renderer {

glm::mat4 perspective(float fov_y, float aspect, float z_near, float z_far) {
  const float t = std::tan(0.5f * fov_y);
  return projection_from_fov(-std::atan(t * aspect), std::atan(t * aspect), std::atan(t), -std::atan(t),
                             z_near, z_far);
}

glm::mat4 projection_from_fov(float angle_left, float angle_right, float angle_up, float angle_down,
                              float z_near, float z_far) {
  const float l = std::tan(angle_left), r = std::tan(angle_right);
  const float u = std::tan(angle_up), d = std::tan(angle_down);
  // Eye looks down -Z, +Y up; clip: x right, y down, z 0 (near) .. 1 (far).
  glm::mat4 p(0.0f);
  p[0][0] = 2.0f / (r - l);
  p[2][0] = (r + l) / (r - l);
  p[1][1] = -2.0f / (u - d);
  p[2][1] = -(u + d) / (u - d);
  p[2][2] = -z_far / (z_far - z_near);
  p[3][2] = -z_far * z_near / (z_far - z_near);
  p[2][3] = -1.0f;
  return p;
}

Bounds compute_bounds(std::span<const float> positions, const glm::mat4& T_world_mesh) {
  Bounds b;
  b.min = glm::vec3(std::numeric_limits<float>::max());
  b.max = glm::vec3(-std::numeric_limits<float>::max());
  for (size_t i = 0; i + 2 < positions.size(); i += 3) {
    const glm::vec3 p =
        glm::vec3(T_world_mesh * glm::vec4(positions[i], positions[i + 1], positions[i + 2], 1.0f));
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  if (positions.size() < 3) b = Bounds{};
  return b;
}

View frame_bounds(const Bounds& bounds, const OrbitCamera& camera, float aspect) {
  const glm::vec3 up = glm::normalize(camera.up);
  // Front axis: +Z unless up is (nearly) Z, then -Y.
  glm::vec3 front = std::abs(up.z) > 0.9f ? glm::vec3(0.0f, -1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
  front = glm::normalize(front - glm::dot(front, up) * up);
  const glm::vec3 side = glm::cross(up, front);
  const float az = glm::radians(camera.azimuth_deg);
  const float el = glm::radians(camera.elevation_deg);
  const glm::vec3 dir = std::cos(el) * (std::cos(az) * front + std::sin(az) * side) + std::sin(el) * up;

  // A point (radius 0) is framed as if 1e-6 across; any real size, however small (a model in km drawn in
  // file units of 1e-9), keeps its own (an absolute floor of 1e-6 left it a speck or nothing).
  const float radius = bounds.radius() > 0.0f ? bounds.radius() : 1e-6f;
  const float fov_y = glm::radians(camera.fov_y_deg);
  const float tan_y = std::tan(0.5f * fov_y), tan_x = tan_y * aspect;
  // Smallest distance at which all 8 box corners project inside the view (5% margin).
  const glm::vec3 right = glm::normalize(glm::cross(up, dir)), cam_up = glm::cross(dir, right);
  float fit = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec3 rel = corner - bounds.centre();
    const float towards = glm::dot(rel, dir);
    fit = std::max(fit, towards + 1.05f * std::abs(glm::dot(rel, right)) / tan_x);
    fit = std::max(fit, towards + 1.05f * std::abs(glm::dot(rel, cam_up)) / tan_y);
  }
  const float distance = camera.distance_scale * (fit > 0.0f ? fit : radius);
  const glm::vec3 target = bounds.centre() + camera.target_offset;
  const glm::vec3 eye = target + dir * distance;

  View view;
  view.view = glm::lookAt(eye, target, up);
  const float reach = radius * 1.5f + glm::length(camera.target_offset);  // the box from the target
  const float z_near = std::max(distance - reach, distance * 0.01f);
  const float z_far = distance + reach;
  view.projection = perspective(fov_y, aspect, z_near, z_far);
  return view;
}

std::array<View, 2> stereo_pair(const View& mono, float ipd) {
  std::array<View, 2> eyes{mono, mono};
  eyes[0].view = glm::translate(glm::mat4(1.0f), glm::vec3(+0.5f * ipd, 0.0f, 0.0f)) * mono.view;
  eyes[1].view = glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f * ipd, 0.0f, 0.0f)) * mono.view;
  return eyes;
}

}  // namespace pushpull::renderer
