#include "rotation.hpp"

#include <Eigen/SVD>
#include <cmath>

namespace pushpull::deform::detail {

namespace {

Eigen::Matrix3d rotation_of(const Eigen::JacobiSVD<Eigen::Matrix3d>& svd) {
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0)
    U.col(2) = -U.col(2);  // singular values are sorted: col 2 smallest
  return U * V.transpose();
}

}  // namespace

Eigen::Matrix3d closest_rotation_svd(const Eigen::Matrix3d& A) {
  return rotation_of(Eigen::JacobiSVD<Eigen::Matrix3d>(A, Eigen::ComputeFullU | Eigen::ComputeFullV));
}

std::optional<Eigen::Matrix3d> closest_rotation_of_rank_two(const Eigen::Matrix3d& A, double relative) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (!(sigma(1) > relative * sigma(0))) return std::nullopt;
  return rotation_of(svd);
}

Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, int max_steps,
                                 double accept_step) {
  const double scale = A.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return q.toRotationMatrix();
  const Eigen::Matrix3d B = A * (1.0 / scale);  // scale-free tolerances
  Eigen::Matrix3d R = q.toRotationMatrix();
  for (int step = 0; step < max_steps; ++step) {
    // f(R exp[w]) = tr(S) + w . a - w^T H w / 2 + O(|w|^3), S = R^T B, a its axial vector,
    // H = tr(S) I - sym(S); at the maximum a = 0 and H is positive (semi)definite.
    const Eigen::Matrix3d S = R.transpose() * B;
    const Eigen::Vector3d a(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
    const double t = S.trace();
    const double h00 = t - S(0, 0), h11 = t - S(1, 1), h22 = t - S(2, 2);
    const double h01 = -0.5 * (S(0, 1) + S(1, 0)), h02 = -0.5 * (S(0, 2) + S(2, 0)),
                 h12 = -0.5 * (S(1, 2) + S(2, 1));
    // Positive definiteness by leading minors, then w = H^-1 a through the adjugate.
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
    const double det = h00 * c00 + h01 * c01 + h02 * c02;
    const double minor2 = h00 * h11 - h01 * h01;
    const bool maximum_basin = h00 > 1e-9 && minor2 > 1e-12 && det > 1e-15;
    const double a2 = a.squaredNorm();
    if (a2 < 1e-28) {
      if (maximum_basin) return R;  // converged to the maximum (not a saddle)
      break;                        // stationary but not a maximum, or A of rank <= 1: use the SVD
    }
    Eigen::Vector3d w;
    if (maximum_basin) {  // Newton step
      const double c11 = h00 * h22 - h02 * h02, c12 = h02 * h01 - h00 * h12, c22 = minor2;
      const double inv_det = 1.0 / det;
      w = Eigen::Vector3d(c00 * a.x() + c01 * a.y() + c02 * a.z(), c01 * a.x() + c11 * a.y() + c12 * a.z(),
                          c02 * a.x() + c12 * a.y() + c22 * a.z()) *
          inv_det;
    } else {  // gradient step of Mueller et al.'s size
      w = a / (std::abs(t) + 1e-12);
    }
    const double w2 = w.squaredNorm();
    if (w2 > 1.0) w /= std::sqrt(w2);  // trust region of one radian
    // q <- q * exp(w / 2) to second order (the normalisation keeps the axis exact).
    q = q * Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z());
    q.coeffs() *= 1.0 / std::sqrt(q.coeffs().squaredNorm());
    R = q.toRotationMatrix();
    // Newton converges quadratically: after a step of 1e-4 rad the error is of order 1e-8 rad.
    if (maximum_basin && w2 < accept_step * accept_step) return R;
  }
  R = closest_rotation_svd(A);
  q = Eigen::Quaterniond(R);
  return R;
}

Eigen::Matrix3d rotation_onto(const Eigen::Matrix3d& A, const Eigen::Vector3d& h, Eigen::Quaterniond& q) {
  const Eigen::Vector3d u = A * h;
  const double scale = A.cwiseAbs().maxCoeff();
  if (!(u.norm() > 1e-12 * scale) || !u.allFinite()) return q.toRotationMatrix();
  q = Eigen::Quaterniond::FromTwoVectors(h, u);
  return q.toRotationMatrix();
}

}  // namespace pushpull::deform::detail
