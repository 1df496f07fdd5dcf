#include "anderson.hpp"

#include <Eigen/Cholesky>
#include <algorithm>

namespace pushpull::deform::detail {

Anderson::Anderson(int window, Eigen::Index dimension)
    : window_(window), dF_(dimension, window), dG_(dimension, window), gram_(window, window) {}

Eigen::VectorXd Anderson::step(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& g) {
  if (count_ == 0) {
    prev_f_ = g - x;
    prev_g_ = g;
    ++count_;
    return g;
  }
  const int column = (count_ - 1) % window_;
  // dF = f - f_prev with f = g - x; prev_f_ and prev_g_ then become f and g (one pass each).
  const Eigen::Index size = x.size();
  double* df = dF_.col(column).data();
  double* dg = dG_.col(column).data();
  double* pf = prev_f_.data();
  double* pg = prev_g_.data();
  for (Eigen::Index i = 0; i < size; ++i) {
    const double fi = g(i) - x(i);
    df[i] = fi - pf[i];
    dg[i] = g(i) - pg[i];
    pf[i] = fi;
    pg[i] = g(i);
  }
  const Eigen::VectorXd& f = prev_f_;
  const int m = std::min(count_, window_);
  ++count_;
  for (int k = 0; k < m; ++k) gram_(column, k) = gram_(k, column) = dF_.col(column).dot(dF_.col(k));
  // gamma = argmin |f - dF gamma|^2 through the (regularised) normal equations, m <= window is tiny.
  const auto dF = dF_.leftCols(m);
  Eigen::MatrixXd normal = gram_.topLeftCorner(m, m);
  const double reg = 1e-10 * std::max(normal.diagonal().maxCoeff(), 1e-300);
  normal.diagonal().array() += reg;
  const Eigen::VectorXd gamma = normal.ldlt().solve(dF.transpose() * f);
  if (!gamma.allFinite()) {
    reset();
    return g;
  }
  return g - dG_.leftCols(m) * gamma;
}

}  // namespace pushpull::deform::detail
