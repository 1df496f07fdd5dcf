#include "anderson.hpp"

#include <Eigen/Cholesky>
#include <algorithm>

namespace pushpull::deform::detail {

Anderson::Anderson(int window, int min_pairs)
    : window_(std::max(window, 1)), min_pairs_(std::clamp(min_pairs, 1, std::max(window, 1))) {}

Anderson::Anderson(int window, Eigen::Index dimension, int min_pairs) : Anderson(window, min_pairs) {
  own_.emplace(window_, dimension);
}

bool Anderson::step(const SecantHistory& history, const Eigen::Ref<const Eigen::VectorXd>& g,
                    Eigen::Ref<Eigen::VectorXd> next, HelperThread* threads) {
  if (reset_pending_) {  // the pair just recorded links an iterate from before the reset
    base_ = history.pairs();
    reset_pending_ = false;
  }
  const int m = static_cast<int>(std::min<long>({history.pairs() - base_, window_, history.stored()}));
  if (m <= 0) return false;
  // gamma = argmin |f - dF gamma|^2 over the newest m pairs, through the (regularised) normal equations.
  Eigen::MatrixXd normal(m, m);
  Eigen::VectorXd dF_f(m);
  for (int a = 0; a < m; ++a) {
    const int ca = history.column(a);
    dF_f(a) = history.f_on_dF()(ca);
    for (int b = 0; b < m; ++b) normal(a, b) = history.ff()(ca, history.column(b));
  }
  const double reg = 1e-10 * std::max(normal.diagonal().maxCoeff(), 1e-300);
  normal.diagonal().array() += reg;
  const Eigen::VectorXd gamma = normal.ldlt().solve(dF_f);
  if (!gamma.allFinite()) {
    reset();
    return false;
  }
  if (m < min_pairs_) return false;  // too few pairs yet to extrapolate from
  return history.extrapolate(g, gamma, next, threads);
}

Eigen::VectorXd Anderson::step(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& g, HelperThread* threads) {
  (void)own_->add(x, g, threads);
  Eigen::VectorXd next(g.size());
  if (!step(*own_, g, next, threads)) return g;
  return next;
}

}  // namespace pushpull::deform::detail
