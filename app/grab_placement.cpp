#include "grab_placement.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pushpull::app {
namespace {

// Translate(to) * RotY(yaw) * Scale(s) * Translate(-from).
Eigen::Matrix4d about(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double yaw, double s) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix() * s;
  M.topLeftCorner<3, 3>() = R;
  M.topRightCorner<3, 1>() = to - R * from;
  return M;
}

double heading(const Eigen::Vector3d& v) { return std::atan2(-v.x(), -v.z()); }  // 0 = along -Z

}  // namespace

GrabPlacement::GrabPlacement(StagePlacement initial, bool scale_on_floor)
    : initial_(initial), current_(initial), scale_on_floor_(scale_on_floor) {}

double GrabPlacement::relative_scale() const {
  return current_.T_stage_model.topLeftCorner<3, 3>().col(0).norm() /
         initial_.T_stage_model.topLeftCorner<3, 3>().col(0).norm();
}

void GrabPlacement::reset() {
  current_ = initial_;
  grabbed_ = {false, false};
}

bool GrabPlacement::update(const std::array<std::optional<GrabHand>, 2>& hands) {
  const std::array<bool, 2> held{hands[0].has_value(), hands[1].has_value()};
  if (held != grabbed_) {
    // The set of grabbing hands changed: a new grab starts from the current placement.
    if (!held[0] && !held[1]) {
      grabbed_ = held;
      const double s = relative_scale();
      if (s != 1.0 && std::abs(s - 1.0) < 0.1) {  // near life size: snap to it, about the last grab point
        Eigen::Vector3d pivot = last_pivot_;
        if (scale_on_floor_)  // (on the base plane below it, whichever hands grabbed last)
          pivot.y() =
              (current_.T_stage_model * initial_.T_stage_model.inverse() * Eigen::Vector4d(0, 0, 0, 1)).y();
        current_ = placement_from(about(pivot, pivot, 0.0, 1.0 / s) * current_.T_stage_model);
        return true;
      }
      return false;
    }
    grabbed_ = held;
    T_at_grab_ = current_.T_stage_model;
    for (int h = 0; h < 2; ++h)
      if (held[size_t(h)]) at_grab_[size_t(h)] = *hands[size_t(h)];
    return false;
  }
  if (!held[0] && !held[1]) return false;
  Eigen::Matrix4d M;
  if (held[0] && held[1]) {
    const Eigen::Vector3d a0 = at_grab_[0].position, b0 = at_grab_[1].position;
    const Eigen::Vector3d a = hands[0]->position, b = hands[1]->position;
    const double d0 = (b0 - a0).norm(), d = (b - a).norm();
    const double s = d0 > 1e-3 ? std::clamp(d / d0, 0.05, 20.0) : 1.0;
    const double yaw = heading(b - a) - heading(b0 - a0);
    // Scaled about the point of the model's base plane (where its wheels stood) below the hands' midpoint, so
    // the model stays on its floor as it grows or shrinks; both hands raised or lowered together lift it.
    const Eigen::Vector3d mid0 = 0.5 * (a0 + b0), mid = 0.5 * (a + b);
    Eigen::Vector3d from = mid0;
    last_pivot_ = mid;
    if (scale_on_floor_) {
      const double base = (T_at_grab_ * initial_.T_stage_model.inverse() * Eigen::Vector4d(0, 0, 0, 1)).y();
      from.y() = base;
      last_pivot_.y() = base + (mid.y() - mid0.y());
    }
    M = about(from, last_pivot_, yaw, s);
  } else {
    const int h = held[0] ? 0 : 1;
    last_pivot_ = hands[size_t(h)]->position;
    M = about(at_grab_[size_t(h)].position, last_pivot_, hands[size_t(h)]->yaw - at_grab_[size_t(h)].yaw, 1.0);
  }
  current_ = placement_from(M * T_at_grab_);
  return true;
}

}  // namespace pushpull::app
