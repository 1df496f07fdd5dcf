// Grip = grab and move the model: the reviewer holds a grip and the model follows the hand (translation and
// turning about the vertical, so it stays upright); with both grips held it also scales with the distance
// between the hands, about the point of its base plane below their midpoint (it stays on the floor its wheels
// stood on; both hands raised together lift it). Releasing within 10% of life size snaps back to life size
// (about the grab point, on the base plane after a two-hand grab), and reset() returns to the initial
// placement (the session's first: life size, on the floor).
// Frames: hand positions in stage space (metres); yaw about stage +Y (radians). Thread-safety: one thread.
#pragma once

#include "stage_placement.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>

namespace pushpull::app {

struct GrabHand {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // stage
  double yaw = 0.0;                                    // heading of the controller about stage +Y
};

class GrabPlacement {
 public:
  // scale_on_floor false: two-hand scaling about the hands' midpoint itself (recordings of format <= 5).
  explicit GrabPlacement(StagePlacement initial, bool scale_on_floor);

  // One frame: the hands whose grip is held (and tracked). Returns true when the placement changed.
  bool update(const std::array<std::optional<GrabHand>, 2>& hands);
  void reset();
  [[nodiscard]] const StagePlacement& placement() const { return current_; }
  [[nodiscard]] bool grabbing() const { return grabbed_[0] || grabbed_[1]; }
  // Size relative to life size (1 = life size).
  [[nodiscard]] double relative_scale() const;

 private:
  StagePlacement initial_, current_;
  Eigen::Matrix4d T_at_grab_ = Eigen::Matrix4d::Identity();  // T_stage_model when the grab (set) began
  bool scale_on_floor_ = true;
  std::array<bool, 2> grabbed_{false, false};
  std::array<GrabHand, 2> at_grab_{};
  Eigen::Vector3d last_pivot_ = Eigen::Vector3d::Zero();
};

}  // namespace pushpull::app
