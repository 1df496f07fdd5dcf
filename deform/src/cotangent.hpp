// Private: half cotangent weights of triangles, the stiffness coefficients of linear finite elements, from
// intrinsically mollified edge lengths so that every triangle's stiffness is positive semidefinite.
//
// Why mollify instead of clamping. A triangle's cotangent stiffness sum_k (cot_k / 2) |x_(k+1) - x_(k+2)|^2
// is the Dirichlet energy of a linear element; it is positive semidefinite (zero only on translations)
// exactly when its three cotangents are those of one Euclidean triangle, i.e. satisfy
// cot a cot b + cot b cot c + cot c cot a = 1. Clamping a cotangent of a sliver breaks that identity and
// makes the element, then the assembled matrix, indefinite (a car body with slivers gave "singular or
// indefinite" and a negative energy). Instead, as in Sharp and Crane 2020 ("A Laplacian for nonmanifold
// triangle meshes", section 4.5), the same small length is added to every edge so that each triangle
// satisfies the triangle inequality by a margin eps, and the cotangents are those of the triangle with the
// mollified lengths (law of cosines, area by Kahan's stable Heron formula). Each element is then the
// Dirichlet form of a valid triangle, PSD by construction, whatever the input (needles, caps, zero-length
// edges), and every weight is bounded: |cot| is at most about (longest edge) / eps. Well-shaped triangles
// are changed only by the tiny added length (relative change <= eps / their edge length); when no triangle
// violates the margin nothing is added.
//
// The sum over elements of PSD forms with non-negative multiplicities (arap-sr, arap-m, arap-n, sr-arap,
// arap-h, asan, and also the spokes of arap-s, whose matrix is twice the cotangent Laplacian) is PSD, and
// positive definite on the free vertices of a region whose every part reaches a constrained vertex.
#pragma once

#include <Eigen/Core>

namespace pushpull::deform::detail {

// Mollification margin relative to a length of the model: eps = kMollifyFactor * reference length, with the
// reference length the mean edge length of the *rest* region (see mollification_margin). 1e-4 bounds the
// weights of any sliver at about 2e4 (longest edge / mean edge) while moving the lengths of ordinary
// triangles by a hundredth of a percent at most.
inline constexpr double kMollifyFactor = 1e-4;

// eps = kMollifyFactor * mean edge length of `faces` on P (0 when there are no faces). Model units.
//
// ASAN stretches the region by tau (eigenvalues mu, 1, 1) before taking cotangents and uses the same eps
// as the rest mesh, not one relative to the stretched mesh's mean edge. tau never shortens an altitude
// (area grows at least as much as any edge) and lengthens edges at most mu times, so a stretched triangle is
// thin by design (|cot| up to ~mu x aspect) but near-degenerate only where the rest one is: a healthy rest
// triangle (altitude ~ edge l) keeps a triangle-inequality margin of at least about 2 l / mu after the
// stretch, some 200 eps for mu = 100, and the anisotropy ASAN wants is left untouched. An eps relative to
// the stretched mean edge (about mu / 2 times larger) would come within a small factor of that margin and
// flatten the very weights that make ASAN.
[[nodiscard]] double mollification_margin(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces);

struct HalfCotangents {
  // 3 * #faces values, index 3 f + k: cot(angle at corner k) / 2 of the mollified triangle f, the weight of
  // the edge opposite corner k (from vertex faces(f,(k+1)%3) to faces(f,(k+2)%3)).
  Eigen::VectorXd values;
  double added_length = 0.0;  // the length added to every edge (model units, >= 0; 0: no triangle needed it)
};

// For every face f (rows of `faces`, indices into the columns of P, 3 by #P positions): the half cotangents
// of the triangle with edge lengths |edge| + delta, where delta >= 0 is the smallest value such that every
// face satisfies l_i + l_j >= l_k + eps for all its corners (eps >= 0, model units). Faces with a repeated
// vertex index or non-finite positions are the caller's to exclude: they are mollified like any other.
[[nodiscard]] HalfCotangents half_cotangents(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces,
                                             double eps);

// The ASAN stretch tau(p) = p + (mu - 1) (p . d_o) / |d_o|^2 d_o of every column of P (Le Vaou et al. eq. 9).
[[nodiscard]] Eigen::Matrix3Xd stretch_along(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& d_o,
                                             double mu);

}  // namespace pushpull::deform::detail
