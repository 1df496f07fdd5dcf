#include "cotangent.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace pushpull::deform::detail {

double mollification_margin(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces) {
  if (faces.rows() == 0) return 0.0;
  double total = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) total += (P.col(faces(f, (k + 1) % 3)) - P.col(faces(f, (k + 2) % 3))).norm();
  }
  return kMollifyFactor * total / (3.0 * static_cast<double>(faces.rows()));
}

HalfCotangents half_cotangents(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces, double eps) {
  const Eigen::Index nf = faces.rows();
  // Edge length opposite each corner, and the smallest length to add so that every triangle inequality
  // holds with margin eps (adding delta to all three lengths raises each margin l_i + l_j - l_k by delta).
  Eigen::Matrix3Xd lengths(3, nf);
  double delta = 0.0;
  for (Eigen::Index f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k)
      lengths(k, f) = (P.col(faces(f, (k + 1) % 3)) - P.col(faces(f, (k + 2) % 3))).norm();
    for (int k = 0; k < 3; ++k) {
      const double margin = lengths((k + 1) % 3, f) + lengths((k + 2) % 3, f) - lengths(k, f);
      delta = std::max(delta, eps - margin);
    }
  }

  HalfCotangents out;
  out.added_length = delta;
  out.values = Eigen::VectorXd::Zero(3 * nf);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Vector3d l = lengths.col(f).array() + delta;
    // Kahan's Heron formula on sorted lengths a >= b >= c, stable for needles and caps.
    double a = l(0), b = l(1), c = l(2);
    if (a < b) std::swap(a, b);
    if (b < c) std::swap(b, c);
    if (a < b) std::swap(a, b);
    const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    const double area = 0.25 * std::sqrt(std::max(product, 0.0));
    if (!(area > 0.0)) continue;  // only possible with eps = 0 on a degenerate face: no stiffness
    const double inv = 1.0 / (8.0 * area);
    for (int k = 0; k < 3; ++k) {
      const double li = l((k + 1) % 3), lj = l((k + 2) % 3), lk = l(k);
      // Law of cosines: cot(angle opposite l_k) = (l_i^2 + l_j^2 - l_k^2) / (4 area); half of it.
      out.values(3 * f + k) = ((li - lk) * (li + lk) + lj * lj) * inv;
    }
  }
  return out;
}

Eigen::Matrix3Xd stretch_along(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& d_o, double mu) {
  const Eigen::Matrix3d tau =
      Eigen::Matrix3d::Identity() + (mu - 1.0) * d_o * d_o.transpose() / d_o.squaredNorm();
  return tau * P;
}

}  // namespace pushpull::deform::detail
