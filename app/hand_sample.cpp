#include "hand_sample.hpp"

#include <Eigen/Geometry>

namespace pushpull::app {

HandSample hand_sample(const xr::HandInput& in) {
  HandSample s;
  s.trigger = in.trigger;
  s.tracked = in.T_stage_aim.has_value();
  if (s.tracked) {
    const XrPosef& p = *in.T_stage_aim;
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z).normalized();
    s.origin_stage = {p.position.x, p.position.y, p.position.z};
    s.direction_stage = q * Eigen::Vector3d(0.0, 0.0, -1.0);
    s.up_stage = q * Eigen::Vector3d(0.0, 1.0, 0.0);
  }
  return s;
}

HandSample hold_untracked(const xr::HandInput& in, std::optional<HandSample>& last_tracked) {
  HandSample s = hand_sample(in);
  if (!s.tracked) return s;
  if (in.aim_position_tracked) {
    last_tracked = s;
    return s;
  }
  if (!last_tracked) {
    s.tracked = false;
    return s;
  }
  s.origin_stage = last_tracked->origin_stage;  // the position is held; the orientation (IMU) stays live
  return s;
}

XrPosef pointer_pose(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  const Eigen::Quaterniond q =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(0, 0, -1), direction.normalized());
  XrPosef pose;
  pose.position = {float(origin.x()), float(origin.y()), float(origin.z())};
  pose.orientation = {float(q.x()), float(q.y()), float(q.z()), float(q.w())};
  return pose;
}

}  // namespace pushpull::app
