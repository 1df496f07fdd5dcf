#include "cotangent.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "pushpull/deform/mesh_validation.hpp"

namespace pushpull::deform::detail {

Eigen::VectorXd half_cotangents(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * faces.rows());
  constexpr double kHalfMax = 0.5 * kMaxCotangent;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = P.col(faces(f, 0)), b = P.col(faces(f, 1)), c = P.col(faces(f, 2));
    const Eigen::Vector3d ab = b - a, bc = c - b, ca = a - c;
    const double twice_area = ab.cross(-ca).norm();
    const double longest2 = std::max({ab.squaredNorm(), bc.squaredNorm(), ca.squaredNorm()});
    if (!(twice_area > 1e-14 * longest2)) continue;  // degenerate: no stiffness
    // cot(angle at a) = (ab . ac) / |ab x ac|, and so on.
    const double inv = 0.5 / twice_area;
    out(3 * f + 0) = std::clamp(ab.dot(-ca) * inv, -kHalfMax, kHalfMax);
    out(3 * f + 1) = std::clamp(bc.dot(-ab) * inv, -kHalfMax, kHalfMax);
    out(3 * f + 2) = std::clamp(ca.dot(-bc) * inv, -kHalfMax, kHalfMax);
  }
  return out;
}

Eigen::Matrix3Xd stretch_along(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& d_o, double mu) {
  const Eigen::Matrix3d tau =
      Eigen::Matrix3d::Identity() + (mu - 1.0) * d_o * d_o.transpose() / d_o.squaredNorm();
  return tau * P;
}

}  // namespace pushpull::deform::detail
