#include "mirror_view.hpp"

#include "orbit_control.hpp"

#include "pushpull/renderer/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <numbers>

namespace pushpull::app {

const char* mirror_mode_name(MirrorMode mode) {
  switch (mode) {
    case MirrorMode::HeadsetEye:
      return "headset eye";
    case MirrorMode::SmoothedFirstPerson:
      return "smoothed first person";
    case MirrorMode::FreeOrbit:
      return "free orbit";
  }
  return "?";
}

MirrorMode next_mirror_mode(MirrorMode mode) {
  switch (mode) {
    case MirrorMode::HeadsetEye:
      return MirrorMode::SmoothedFirstPerson;
    case MirrorMode::SmoothedFirstPerson:
      return MirrorMode::FreeOrbit;
    case MirrorMode::FreeOrbit:
      return MirrorMode::HeadsetEye;
  }
  return MirrorMode::HeadsetEye;
}

void MirrorView::set_mode(MirrorMode mode) {
  if (mode == MirrorMode::FreeOrbit && mode_ != MirrorMode::FreeOrbit) {
    // Start from the reviewer's side: the orbit's azimuth is measured from +Z towards +X around +Y, the
    // camera sits opposite to where the reviewer looks.
    orbit_ = renderer::OrbitCamera{};
    orbit_.azimuth_deg = float(head_yaw_ * 180.0 / std::numbers::pi);
    orbit_.elevation_deg = 20.0f;
  }
  mode_ = mode;
}

void MirrorView::pointer(const renderer::MirrorWindow::Pointer& p) {
  if (mode_ == MirrorMode::FreeOrbit) {
    const bool held = last_pointer_ && (p.left || p.right) && (last_pointer_->left || last_pointer_->right);
    orbit_with_pointer(orbit_, p, last_pointer_.value_or(p), held);
  }
  last_pointer_ = p;
}

renderer::View MirrorView::update(const std::array<xr::EyeView, 2>& eyes, double dt_s, float aspect) {
  const xr::EyeView& left = eyes[0];
  const float fov_y = left.fov.angleUp - left.fov.angleDown;
  const glm::quat q(left.T_stage_eye.orientation.w, left.T_stage_eye.orientation.x, left.T_stage_eye.orientation.y,
                    left.T_stage_eye.orientation.z);
  const auto& p0 = eyes[0].T_stage_eye.position;
  const auto& p1 = eyes[1].T_stage_eye.position;
  // The head looks between the eyes: displays may be canted outwards, each eye turned by a few degrees.
  const auto& r = eyes[1].T_stage_eye.orientation;
  const glm::quat head_q = glm::slerp(q, glm::quat(r.w, r.x, r.y, r.z), 0.5f);
  {
    const glm::vec3 f = head_q * glm::vec3(0.0f, 0.0f, -1.0f);
    head_yaw_ = std::atan2(-double(f.x), -double(f.z));
  }
  if (mode_ == MirrorMode::FreeOrbit) return renderer::frame_bounds(bounds_, orbit_, aspect);
  renderer::View view;
  view.projection = renderer::perspective(fov_y, aspect, 0.05f, 100.0f);
  if (mode_ == MirrorMode::HeadsetEye) {
    glm::mat4 T_stage_eye = glm::mat4_cast(q);
    T_stage_eye[3] = glm::vec4(p0.x, p0.y, p0.z, 1.0f);
    view.view = glm::inverse(T_stage_eye);
    position_.reset();
    return view;
  }
  const glm::dvec3 head(0.5 * (double(p0.x) + p1.x), 0.5 * (double(p0.y) + p1.y), 0.5 * (double(p0.z) + p1.z));
  const glm::dvec3 forward = glm::dvec3(head_q * glm::vec3(0.0f, 0.0f, -1.0f));
  const double yaw = std::atan2(-forward.x, -forward.z);  // 0 = looking down -Z
  const double pitch = std::asin(std::clamp(forward.y, -1.0, 1.0));
  const double alpha = 1.0 - std::exp(-std::max(dt_s, 0.0) / 0.5);
  if (!position_) {
    position_ = head;
    yaw_ = yaw;
  } else {
    *position_ += alpha * (head - *position_);
    double delta = std::remainder(yaw - yaw_, 2.0 * std::numbers::pi);  // the short way round
    yaw_ += alpha * delta;
  }
  const glm::dvec3 look(-std::sin(yaw_) * std::cos(pitch), std::sin(pitch), -std::cos(yaw_) * std::cos(pitch));
  view.view = glm::lookAt(glm::vec3(*position_), glm::vec3(*position_ + look), glm::vec3(0.0f, 1.0f, 0.0f));
  return view;
}

}  // namespace pushpull::app
