// Cameras: view and projection matrices in the renderer's conventions (types.hpp: View).
// Thread-safety: pure functions.
#pragma once

#include "pushpull/renderer/types.hpp"

#include <glm/glm.hpp>

#include <array>
#include <span>

namespace pushpull::renderer {

// Perspective projection to Vulkan clip space (y down, depth 0..1). fov_y in radians, aspect = w/h.
glm::mat4 perspective(float fov_y, float aspect, float z_near, float z_far);

// Asymmetric projection from the four half-angles an XR runtime reports (XrFovf: left and down
// negative), radians.
glm::mat4 projection_from_fov(float angle_left, float angle_right, float angle_up, float angle_down,
                              float z_near, float z_far);

// Axis-aligned bounds of positions (#V*3 floats), optionally transformed.
struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
  [[nodiscard]] glm::vec3 centre() const { return 0.5f * (min + max); }
  [[nodiscard]] float radius() const { return 0.5f * glm::length(max - min); }
};
Bounds compute_bounds(std::span<const float> positions, const glm::mat4& T_world_mesh = glm::mat4(1.0f));

// Orbit camera parameters; angles in degrees. Azimuth is measured around `up` from the +Z axis
// (glTF front) towards +X; elevation above the horizontal plane.
struct OrbitCamera {
  float azimuth_deg = 35.0f;
  float elevation_deg = 20.0f;
  float fov_y_deg = 30.0f;
  float distance_scale = 1.0f;  // 1 = the bounding box just fits the view (5% margin); < 1 zooms in
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  glm::vec3 target_offset{0.0f};  // the point looked at: the box's centre plus this (world units)
};

// A view looking at the centre of `bounds` (plus camera.target_offset) from direction (azimuth, elevation),
// at distance_scale times the smallest distance where all 8 box corners are inside the view when looking at
// the centre (aspect = width / height).
View frame_bounds(const Bounds& bounds, const OrbitCamera& camera, float aspect);

// Stereo pair around a mono view: eyes offset by +-ipd/2 along the view's x axis, same projection.
std::array<View, 2> stereo_pair(const View& mono, float ipd);

}  // namespace pushpull::renderer
