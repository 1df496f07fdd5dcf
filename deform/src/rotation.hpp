// Private: the rotation R in SO(3) closest to a 3x3 matrix A, i.e. maximising R : A (trace(R^T A)); the
// rotational factor of the polar decomposition with det R = +1.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace pushpull::deform::detail {

// Reference: SVD A = U S V^T, R = U diag(1, 1, det(U V^T)) V^T (flipping the singular vector of the
// smallest singular value when A would give a reflection). About 1 microsecond.
[[nodiscard]] Eigen::Matrix3d closest_rotation_svd(const Eigen::Matrix3d& A);

// The same from the same SVD, empty where A's second singular value is at most `relative` times its first
// (rank <= 1: the twist about the one direction is undetermined).
[[nodiscard]] std::optional<Eigen::Matrix3d> closest_rotation_of_rank_two(const Eigen::Matrix3d& A,
                                                                          double relative);

// Fast path, warm-started from q (updated in place): Newton's method on SO(3) for max R : A, in the body
// frame R <- R exp([w]) with w = H^-1 a, where S = R^T A, a = axial vector of S - S^T and
// H = tr(S) I - sym(S) (the gradient and Hessian of the trace). Converges quadratically from a warm start
// (1-2 steps per call once the solver settles). Where H is not positive definite it takes the gradient step
// w = a / |tr S| of Mueller, Bender, Chentanez, Macklin 2016 ("A robust method to extract the rotational
// part of deformations"). Falls back to closest_rotation_svd when it ends at a saddle, A has rank <= 1, or
// it has not converged after max_steps; A ~ 0 returns the warm start. Returns the rotation matrix of q.
// `accept_step`: a Newton step shorter than this (radians) ends the iteration; the remaining error is of
// order accept_step^2 (1e-4: ~1e-8 rad). The solver passes a looser value once warm: an inexact but
// ascending local step keeps the local-global energy non-increasing and the error vanishes with the moves.
Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& A, Eigen::Quaterniond& q, int max_steps = 20,
                                 double accept_step = 1e-4);

// The same maximum for a covariance of rank one, A = u h^T with h a known unit vector (the arap-h bending
// clusters): R : A = u . R h is largest for every R with R h = u / |u|, a circle of rotations. Returns the
// smallest one (about the axis h x u) and stores it in q; A h ~ 0 (any R is optimal) returns the warm start
// q.
Eigen::Matrix3d rotation_onto(const Eigen::Matrix3d& A, const Eigen::Vector3d& h, Eigen::Quaterniond& q);

}  // namespace pushpull::deform::detail
