#include "error_estimate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

namespace pushpull::deform::detail {

ContractionEstimate::ContractionEstimate(int window, Eigen::Index dimension, Policy policy,
                                         bool exact_local_fit)
    : window_(window),
      policy_(policy),
      contracting_only_(exact_local_fit && policy != Policy::Cautious),
      dX_(dimension, window),
      dG_(dimension, window),
      xx_(Eigen::MatrixXd::Zero(window, window)),
      xg_(Eigen::MatrixXd::Zero(window, window)) {}

void ContractionEstimate::add(const Eigen::Ref<const Eigen::VectorXd>& x,
                              const Eigen::Ref<const Eigen::VectorXd>& g, HelperThread* threads) {
  if (!has_previous_) {
    previous_x_ = x;
    previous_g_ = g;
    has_previous_ = true;
    return;
  }
  const int column = pairs_ % window_;
  ++pairs_;
  // The new secant pair, and the Gram matrices dX^T dX and dX^T dG with one row and column refreshed per
  // pair (O(window n) per call), over the two halves of the vectors.
  const int m = std::min(pairs_, window_);
  const Eigen::Index n = x.size(), half = n / 2;
  Eigen::MatrixXd partial = Eigen::MatrixXd::Zero(3 * m, 2);
  auto part = [&](int p) {
    const Eigen::Index begin = p == 0 ? 0 : half, size = p == 0 ? half : n - half;
    auto dx = dX_.col(column).segment(begin, size);
    auto dg = dG_.col(column).segment(begin, size);
    dx = x.segment(begin, size) - previous_x_.segment(begin, size);
    dg = g.segment(begin, size) - previous_g_.segment(begin, size);
    previous_x_.segment(begin, size) = x.segment(begin, size);
    previous_g_.segment(begin, size) = g.segment(begin, size);
    for (int k = 0; k < m; ++k) {
      partial(3 * k, p) = dx.dot(dX_.col(k).segment(begin, size));
      partial(3 * k + 1, p) = dx.dot(dG_.col(k).segment(begin, size));
      partial(3 * k + 2, p) = dX_.col(k).segment(begin, size).dot(dg);
    }
  };
  if (threads) {
    threads->run_both(part);
  } else {
    part(0);
    part(1);
  }
  for (int k = 0; k < m; ++k) {
    xx_(column, k) = xx_(k, column) = partial(3 * k, 0) + partial(3 * k, 1);
    xg_(column, k) = partial(3 * k + 1, 0) + partial(3 * k + 1, 1);
    xg_(k, column) = partial(3 * k + 2, 0) + partial(3 * k + 2, 1);
  }
  if (pairs_ < window_) return;
  // C = argmin |dX C - dG| through the normal equations (regularised: dX may be nearly rank deficient once
  // converged).
  Eigen::MatrixXd normal = xx_;
  normal.diagonal().array() += 1e-12 * std::max(normal.diagonal().maxCoeff(), 1e-300);
  const Eigen::MatrixXd C = normal.ldlt().solve(xg_);
  if (!C.allFinite()) return;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(C, /*computeEigenvectors=*/false);
  if (eigen.info() != Eigen::Success) return;
  // Recent and Warm with an exact local fit: Ritz values with a non-positive real part are left out
  // (error_estimate.hpp says why); a window whose values are all left out says nothing and is no estimate.
  double largest = 0.0;
  bool any = false;
  for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) {
    const std::complex<double> value = eigen.eigenvalues()(k);
    if (contracting_only_ && !(value.real() > 0.0)) continue;
    largest = std::max(largest, std::abs(value));
    any = true;
  }
  if (!any || !std::isfinite(largest)) return;
  recent_[static_cast<std::size_t>(estimates_++ % recent_.size())] = largest;
  double recent_largest = 0.0;
  for (std::size_t k = 0; k < std::min<std::size_t>(recent_.size(), static_cast<std::size_t>(estimates_));
       ++k)
    recent_largest = std::max(recent_largest, recent_[k]);
  if (policy_ == Policy::Cautious) {
    expanding_ = recent_largest >= 1.0;
    whole_solve_ = std::max(whole_solve_, std::min(largest, kCautiousMaxRate));
    rate_ = whole_solve_;
  } else {
    // The largest of the later half of the solve's estimates [estimates_ / 2, estimates_), and at least the
    // last 10: a sliding maximum (indices of decreasing values; both window ends only move forward).
    const long index = estimates_ - 1;
    while (!later_.empty() && later_.back().second <= largest) later_.pop_back();
    later_.emplace_back(index, largest);
    while (later_.front().first < estimates_ / 2) later_.pop_front();
    recent_only_ = std::min(recent_largest, kMaxRate);
    rate_ = policy_ == Policy::Warm ? recent_only_
                                    : std::min(std::max(later_.front().second, recent_largest), kMaxRate);
  }
}

std::optional<double> ContractionEstimate::rate() const {
  if (expanding_) return std::nullopt;
  const bool any = pairs_ >= window_;  // at least one estimate
  const long needed = policy_ == Policy::Cautious ? static_cast<long>(recent_.size()) : window_;
  if (!any || estimates_ < needed) {  // too few of its own: the floor alone (a warm start's), or none
    if (policy_ == Policy::Cautious || !floor_) return std::nullopt;
    return any ? std::max(rate_, *floor_) : *floor_;
  }
  return floor_ ? std::max(rate_, *floor_) : rate_;
}

std::optional<double> ContractionEstimate::recent_rate() const {
  const std::optional<double> all = rate();
  if (!all || policy_ == Policy::Cautious || pairs_ < window_ || estimates_ < window_) return all;
  return floor_ ? std::max(recent_only_, *floor_) : recent_only_;
}

void ContractionEstimate::set_floor(double rate) {
  if (!(rate >= 0.0)) return;  // also NaN
  floor_ = std::min(rate, policy_ == Policy::Cautious ? kCautiousMaxRate : kMaxRate);
}

}  // namespace pushpull::deform::detail
