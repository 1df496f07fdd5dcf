// Private: half cotangent weights of triangles, the stiffness coefficients of linear finite elements.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pushpull::deform::detail {

// For every face f (rows of `faces`, indices into the columns of P, 3 by #P positions) and corner k, the
// value cot(angle at corner k) / 2, the weight of the edge opposite corner k (from vertex faces(f,(k+1)%3) to
// faces(f,(k+2)%3)). Faces with zero area (relative to their longest edge squared, 1e-14) get zeros;
// others are clamped to +-kMaxCotangent / 2. Returned as a vector of size 3 * #faces, index 3 f + k.
[[nodiscard]] Eigen::VectorXd half_cotangents(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces);

// The ASAN stretch tau(p) = p + (mu - 1) (p . d_o) / |d_o|^2 d_o of every column of P (Le Vaou et al. eq. 9).
[[nodiscard]] Eigen::Matrix3Xd stretch_along(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& d_o,
                                             double mu);

}  // namespace pushpull::deform::detail
