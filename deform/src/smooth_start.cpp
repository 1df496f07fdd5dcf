// The cold solve's biharmonic starting shape (smooth_start.hpp).
#include "smooth_start.hpp"

#include <vector>

namespace pushpull::deform::detail {

void SmoothStart::prepare(const Eigen::SparseMatrix<double>& pattern, const GlobalSystem& analysed) {
  prepared_ = false;
  n_free_ = analysed.free_count();
  laplacian_ = pattern;
  for (int j = 0; j < laplacian_.outerSize(); ++j) {
    double degree = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian_, j); it; ++it) {
      if (it.row() != j) {
        it.valueRef() = -1.0;
        degree += 1.0;
      }
    }
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian_, j); it; ++it)
      if (it.row() == j) it.valueRef() = degree;
  }
  if (n_free_ > 0) {
    system_.analyze_like(analysed);
    system_.factorize(laplacian_);
  }
  prepared_ = true;
}

Eigen::Matrix3Xd SmoothStart::apply_squared(const Eigen::Matrix3Xd& X_f, const Eigen::Matrix3Xd& X_c) const {
  const Eigen::Index n = laplacian_.cols();
  Eigen::Matrix3Xd X(3, n);
  X.leftCols(n_free_) = X_f;
  X.rightCols(n - n_free_) = X_c;
  const Eigen::Matrix3Xd LX = X * laplacian_;  // L is symmetric: (L X^T)^T
  return (LX * laplacian_).leftCols(n_free_);
}

SmoothStart::Spread SmoothStart::displacement(const Eigen::Matrix3Xd& D_c, HelperThread* threads) const {
  Spread out;
  out.free = Eigen::Matrix3Xd::Zero(3, n_free_);
  if (n_free_ == 0) {
    out.converged = true;
    return out;
  }
  const Eigen::Matrix3Xd zero_c = Eigen::Matrix3Xd::Zero(3, D_c.cols());
  // The harmonic spread: L_ff X = -L_fc D_c.
  Eigen::Matrix3Xd& X = out.free;
  X = system_.constrained_rhs(D_c);
  system_.solve_in_place(X, threads);
  // Residual of (L^2)_ff X = -(L^2)_fc D_c, i.e. r = -(L^2 [X; D_c])_f.
  Eigen::Matrix3Xd r = -apply_squared(X, D_c);
  const Eigen::Vector3d r0 = r.rowwise().norm();
  auto precondition = [&](const Eigen::Matrix3Xd& v) {
    Eigen::Matrix3Xd z = v;
    system_.solve_in_place(z, threads);
    system_.solve_in_place(z, threads);
    return z;
  };
  auto done = [&](int c) { return !(r.row(c).norm() > kTolerance * r0[c]); };
  Eigen::Matrix3Xd z = precondition(r);
  Eigen::Matrix3Xd p = z;
  Eigen::Vector3d rz = r.cwiseProduct(z).rowwise().sum();
  out.converged = done(0) && done(1) && done(2);
  while (!out.converged && out.iterations < kMaxIterations) {
    const Eigen::Matrix3Xd Ap = apply_squared(p, zero_c);
    const Eigen::Vector3d pAp = p.cwiseProduct(Ap).rowwise().sum();
    for (int c = 0; c < 3; ++c) {
      if (done(c) || !(pAp[c] > 0.0)) continue;  // a finished coordinate keeps its value
      const double alpha = rz[c] / pAp[c];
      X.row(c) += alpha * p.row(c);
      r.row(c) -= alpha * Ap.row(c);
    }
    ++out.iterations;
    out.converged = done(0) && done(1) && done(2);
    if (out.converged) break;
    z = precondition(r);
    const Eigen::Vector3d rz_next = r.cwiseProduct(z).rowwise().sum();
    for (int c = 0; c < 3; ++c) {
      const double beta = rz[c] > 0.0 ? rz_next[c] / rz[c] : 0.0;
      p.row(c) = z.row(c) + beta * p.row(c);
    }
    rz = rz_next;
  }
  if (!X.allFinite())
    X.setZero();  // cannot happen for finite D_c and a positive definite L_ff; never pass NaN on
  return out;
}

}  // namespace pushpull::deform::detail
