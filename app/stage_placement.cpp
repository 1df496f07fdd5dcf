#include "stage_placement.hpp"

#include <cmath>
#include <stdexcept>

namespace pushpull::app {

Eigen::Vector3d StagePlacement::to_model_point(const Eigen::Vector3d& p) const {
  return T_model_stage.topLeftCorner<3, 3>() * p + T_model_stage.topRightCorner<3, 1>();
}
Eigen::Vector3d StagePlacement::to_model_vector(const Eigen::Vector3d& v) const {
  return T_model_stage.topLeftCorner<3, 3>() * v;
}
Eigen::Vector3d StagePlacement::to_stage_point(const Eigen::Vector3d& p) const {
  return T_stage_model.topLeftCorner<3, 3>() * p + T_stage_model.topRightCorner<3, 1>();
}

StagePlacement placement_from(const Eigen::Matrix4d& T) {
  StagePlacement p;
  p.T_stage_model = T;
  const Eigen::Matrix3d A = T.topLeftCorner<3, 3>();
  const double s2 = A.col(0).squaredNorm();  // uniform scale squared
  const Eigen::Matrix3d A_inv = A.transpose() / s2;
  p.T_model_stage.topLeftCorner<3, 3>() = A_inv;
  p.T_model_stage.topRightCorner<3, 1>() = -A_inv * T.topRightCorner<3, 1>();
  return p;
}

StagePlacement place_on_stage(const Eigen::MatrixXd& V, const PlacementOptions& o) {
  if (V.rows() == 0) throw std::invalid_argument("place_on_stage: the model has no vertices");
  if (!(o.scale > 0.0)) throw std::invalid_argument("place_on_stage: the scale must be > 0");
  // An axis whose plain norm overflows or underflows (--up 1e308 1e308 1e308) is scaled by its stable norm
  // first (it squashed the model to nothing); other axes keep the plain path's bits.
  auto axis = [](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    const double plain = v.norm(), stable = v.stableNorm();
    if (plain > 0.0 && std::isfinite(plain)) return v;
    return stable > 0.0 && std::isfinite(stable) ? Eigen::Vector3d(v / stable) : Eigen::Vector3d::Zero();
  };
  const Eigen::Vector3d up_model = axis(o.up_model), front_model = axis(o.front_model);
  if (up_model.norm() == 0.0) throw std::invalid_argument("place_on_stage: the up axis is zero");
  const Eigen::Vector3d up = up_model.normalized();
  const Eigen::Vector3d front_in = front_model - front_model.dot(up) * up;
  if (front_in.norm() < 1e-9 * std::max(1.0, front_model.norm()))
    throw std::invalid_argument("place_on_stage: the front axis is zero or parallel to the up axis");
  const Eigen::Vector3d front = front_in.normalized();
  const Eigen::Vector3d right = up.cross(front);
  Eigen::Matrix3d R;  // rows: where stage x, y, z come from
  R.row(0) = right.transpose();
  R.row(1) = up.transpose();
  R.row(2) = front.transpose();
  const Eigen::Matrix3d A = o.scale * R;

  const Eigen::MatrixXd S = (V * A.transpose());  // #V by 3, rotated and scaled, before translation
  const Eigen::Vector3d lo = S.colwise().minCoeff().transpose(), hi = S.colwise().maxCoeff().transpose();
  const Eigen::Vector3d t(-0.5 * (lo.x() + hi.x()), -lo.y(), -hi.z() - o.distance_m);

  StagePlacement placement;
  placement.T_stage_model.topLeftCorner<3, 3>() = A;
  placement.T_stage_model.topRightCorner<3, 1>() = t;
  const Eigen::Matrix3d A_inv = R.transpose() / o.scale;
  placement.T_model_stage.topLeftCorner<3, 3>() = A_inv;
  placement.T_model_stage.topRightCorner<3, 1>() = -A_inv * t;
  return placement;
}

}  // namespace pushpull::app
