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
      dimension_(dimension) {}

void ContractionEstimate::add(const Eigen::Ref<const Eigen::VectorXd>& x,
                              const Eigen::Ref<const Eigen::VectorXd>& g, HelperThread* threads) {
  if (!own_) own_.emplace(window_, dimension_);
  (void)own_->add(x, g, threads);
  add(*own_);
}

void ContractionEstimate::add(const SecantHistory& history) {
  pairs_ = history.pairs();
  if (history.pairs() < window_ || history.stored() < window_) return;
  // The newest `window` pairs: dX^T dX and dX^T dG from the stored dF and dG (dX = dG - dF).
  const int m = window_;
  Eigen::MatrixXd xx(m, m), xg(m, m);
  for (int a = 0; a < m; ++a) {
    const int ca = history.column(a);
    for (int b = 0; b < m; ++b) {
      const int cb = history.column(b);
      xg(a, b) = history.gg()(ca, cb) - history.fg()(ca, cb);
      xx(a, b) = history.gg()(ca, cb) - history.fg()(ca, cb) - history.fg()(cb, ca) + history.ff()(ca, cb);
    }
  }
  // C = argmin |dX C - dG| through the normal equations (regularised: dX may be nearly rank deficient once
  // converged).
  Eigen::MatrixXd normal = xx;
  normal.diagonal().array() += 1e-12 * std::max(normal.diagonal().maxCoeff(), 1e-300);
  const Eigen::MatrixXd C = normal.ldlt().solve(xg);
  if (!C.allFinite()) return;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(C, /*computeEigenvectors=*/false);
  if (eigen.info() != Eigen::Success) return;
  // Recent and Warm with an exact local fit: Ritz values outside (0, 1) in real part or modulus are left out
  // (error_estimate.hpp says why); a window whose values are all left out says nothing and is no estimate.
  double largest = 0.0;
  bool any = false;
  for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) {
    const std::complex<double> value = eigen.eigenvalues()(k);
    if (contracting_only_ && !(value.real() > 0.0 && std::abs(value) < 1.0)) continue;
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
