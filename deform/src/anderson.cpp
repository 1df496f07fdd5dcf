#include "anderson.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <utility>

namespace pushpull::deform::detail {

Anderson::Anderson(int window, Eigen::Index dimension, int min_pairs)
    : window_(std::max(window, 1)),
      min_pairs_(std::clamp(min_pairs, 1, std::max(window, 1))),
      dF_(dimension, window_),
      dG_(dimension, window_),
      gram_(window_, window_) {}

Eigen::VectorXd Anderson::step(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& g, HelperThread* threads) {
  if (count_ == 0) {
    prev_f_ = g - x;
    prev_g_ = g;
    ++count_;
    return g;
  }
  const int column = (count_ - 1) % window_;
  const int m = std::min(count_, window_);
  ++count_;
  const Eigen::Index n = x.size(), half = n / 2;
  auto range = [&](int p) {
    return std::pair<Eigen::Index, Eigen::Index>(p == 0 ? 0 : half, p == 0 ? half : n);
  };
  // dF = f - f_prev with f = g - x; prev_f_ and prev_g_ then become f and g (one pass each); then the new
  // row and column of dF^T dF and dF^T f, per half.
  Eigen::MatrixXd partial = Eigen::MatrixXd::Zero(2 * m, 2);
  auto update = [&](int p) {
    const auto [begin, end] = range(p);
    double* df = dF_.col(column).data();
    double* dg = dG_.col(column).data();
    double* pf = prev_f_.data();
    double* pg = prev_g_.data();
    for (Eigen::Index i = begin; i < end; ++i) {
      const double fi = g(i) - x(i);
      df[i] = fi - pf[i];
      dg[i] = g(i) - pg[i];
      pf[i] = fi;
      pg[i] = g(i);
    }
    const auto new_column = dF_.col(column).segment(begin, end - begin);
    for (int k = 0; k < m; ++k) {
      partial(k, p) = new_column.dot(dF_.col(k).segment(begin, end - begin));
      partial(m + k, p) = dF_.col(k).segment(begin, end - begin).dot(prev_f_.segment(begin, end - begin));
    }
  };
  if (threads) {
    threads->run_both(update);
  } else {
    update(0);
    update(1);
  }
  Eigen::VectorXd dF_f(m);
  for (int k = 0; k < m; ++k) {
    gram_(column, k) = gram_(k, column) = partial(k, 0) + partial(k, 1);
    dF_f(k) = partial(m + k, 0) + partial(m + k, 1);
  }
  // gamma = argmin |f - dF gamma|^2 through the (regularised) normal equations, m <= window is tiny.
  Eigen::MatrixXd normal = gram_.topLeftCorner(m, m);
  const double reg = 1e-10 * std::max(normal.diagonal().maxCoeff(), 1e-300);
  normal.diagonal().array() += reg;
  const Eigen::VectorXd gamma = normal.ldlt().solve(dF_f);
  if (!gamma.allFinite()) {
    reset();
    return g;
  }
  if (m < min_pairs_) return g;  // too few pairs yet to extrapolate from
  Eigen::VectorXd next(n);
  auto combine = [&](int p) {
    const auto [begin, end] = range(p);
    next.segment(begin, end - begin) =
        g.segment(begin, end - begin) - dG_.middleRows(begin, end - begin).leftCols(m) * gamma;
  };
  if (threads) {
    threads->run_both(combine);
  } else {
    combine(0);
    combine(1);
  }
  return next;
}

}  // namespace pushpull::deform::detail
