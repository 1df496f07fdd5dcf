#include "head_anchor.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace pushpull::app {
namespace {

constexpr double kStillDistance = 0.01;  // metres
constexpr double kStillYaw = 0.01;       // radians

}  // namespace

HeadAnchor anchor_at_head(double time, const Eigen::Vector3d& position, const Eigen::Vector3d& forward) {
  HeadAnchor a;
  a.time = time;
  const double horizontal = std::hypot(forward.x(), forward.z());
  // R_y(yaw) (0, 0, -1) = (-sin yaw, 0, -cos yaw) is the heading.
  if (horizontal > 0.1 * forward.norm()) a.yaw = std::atan2(-forward.x(), -forward.z());
  a.x = position.x();
  a.z = position.z();
  if (!(position.y() >= kFloorLevelHeadMin && position.y() <= kFloorLevelHeadMax))
    a.floor_y = position.y() - kAssumedEyeHeight;
  if (!std::isfinite(a.x) || !std::isfinite(a.z) || !std::isfinite(a.yaw) || !std::isfinite(a.floor_y))
    a = HeadAnchor{time};
  if (std::hypot(a.x, a.z) <= kStillDistance && std::abs(a.yaw) <= kStillYaw && a.floor_y == 0.0)
    a = HeadAnchor{time};
  return a;
}

StagePlacement anchored(const StagePlacement& at_origin, const HeadAnchor& anchor) {
  if (anchor.x == 0.0 && anchor.z == 0.0 && anchor.yaw == 0.0 && anchor.floor_y == 0.0) return at_origin;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(anchor.yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T(0, 3) = anchor.x;
  T(1, 3) = anchor.floor_y;
  T(2, 3) = anchor.z;
  return placement_from(T * at_origin.T_stage_model);
}

std::optional<HeadAnchor> AnchorSchedule::take(double t, double half_frame,
                                               const std::optional<Eigen::Vector3d>& head_position,
                                               const Eigen::Vector3d& head_forward) {
  if (done_) return std::nullopt;
  std::optional<HeadAnchor> anchor;
  if (!recorded_) {
    if (head_position) anchor = anchor_at_head(t, *head_position, head_forward);
  } else if (!recorded_->has_value()) {
    done_ = true;
  } else if ((*recorded_)->time <= t + half_frame) {
    anchor = **recorded_;
  }
  if (anchor) done_ = true;
  return anchor;
}

}  // namespace pushpull::app
