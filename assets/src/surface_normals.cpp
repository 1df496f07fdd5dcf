#include "surface_normals.hpp"

namespace pushpull::assets::detail {

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // length = 2 * area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double length = N.row(v).norm();
    if (length > 0.0 && std::isfinite(length))
      N.row(v) /= length;
    else
      N.row(v).setZero();
  }
  return N;
}

Eigen::Matrix3d rotation_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  if (from.squaredNorm() < 0.5 || to.squaredNorm() < 0.5) return Eigen::Matrix3d::Identity();
  return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

}  // namespace pushpull::assets::detail
