// Area-weighted vertex normals of a triangle mesh, and the rotation that carries a render normal
// from the undeformed to the deformed surface. Thread-safety: pure functions.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pushpull::assets::detail {

// V: #V by 3, F: #F by 3. Returns #V by 3 unit normals (zero rows for isolated vertices).
Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// The smallest rotation taking unit `from` to unit `to` (identity when either is zero).
Eigen::Matrix3d rotation_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

}  // namespace pushpull::assets::detail
