// Where the model stands in the review: T_stage_model, the similarity that maps model coordinates (file
// units) to stage coordinates (metres; OpenXR STAGE: +Y up, the reviewer at the origin looking down -Z).
//
// The placement: life size (scale = metres per file unit, life_size.hpp), the model's up axis to stage +Y
// and its front axis to stage +Z (towards the reviewer), the lowest point on the floor (y = 0: the wheels of
// a car), centred left-right in front of the reviewer, its nearest point `distance_m` in front of them.
//
// The headset loop then moves this placement in front of the reviewer's head (head_anchor.hpp).
//
// Thread-safety: plain values and pure functions.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pushpull::app {

struct PlacementOptions {
  Eigen::Vector3d up_model{0.0, 1.0, 0.0};     // model frame (glTF: +Y)
  Eigen::Vector3d front_model{0.0, 0.0, 1.0};  // model frame (glTF: +Z); made orthogonal to up
  double scale = 1.0;                          // metres per file unit (> 0)
  double distance_m = 0.6;                     // gap between the reviewer and the model's nearest point
};

struct StagePlacement {
  Eigen::Matrix4d T_stage_model = Eigen::Matrix4d::Identity();  // rotation * uniform scale, translation
  Eigen::Matrix4d T_model_stage = Eigen::Matrix4d::Identity();  // its inverse

  [[nodiscard]] Eigen::Vector3d to_model_point(const Eigen::Vector3d& p_stage) const;
  [[nodiscard]] Eigen::Vector3d to_model_vector(const Eigen::Vector3d& v_stage) const;  // no translation
  [[nodiscard]] Eigen::Vector3d to_stage_point(const Eigen::Vector3d& p_model) const;
};

// A placement from T_stage_model (rotation * uniform scale > 0, translation); computes the inverse.
StagePlacement placement_from(const Eigen::Matrix4d& T_stage_model);

// V: #V by 3 model positions (file units). Throws std::invalid_argument when V is empty, scale <= 0, or up
// and front are zero or parallel.
StagePlacement place_on_stage(const Eigen::MatrixXd& V, const PlacementOptions& options);

}  // namespace pushpull::app
