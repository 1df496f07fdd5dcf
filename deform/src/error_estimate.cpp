#include "error_estimate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace pushpull::deform::detail {

ContractionEstimate::ContractionEstimate(int window, Eigen::Index dimension)
    : window_(window), dX_(dimension, window), dG_(dimension, window) {}

void ContractionEstimate::add(const Eigen::Ref<const Eigen::VectorXd>& x,
                              const Eigen::Ref<const Eigen::VectorXd>& g) {
  if (!has_previous_) {
    previous_x_ = x;
    previous_g_ = g;
    has_previous_ = true;
    return;
  }
  const int column = pairs_ % window_;
  dX_.col(column) = x - previous_x_;
  dG_.col(column) = g - previous_g_;
  previous_x_ = x;
  previous_g_ = g;
  ++pairs_;
  if (pairs_ < window_) return;
  // C = argmin |dX C - dG| (column-pivoted QR: dX may be nearly rank deficient once converged).
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(dX_);
  if (qr.rank() == 0) return;
  const Eigen::MatrixXd C = qr.solve(dG_);
  if (!C.allFinite()) return;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(C, /*computeEigenvectors=*/false);
  if (eigen.info() != Eigen::Success) return;
  double largest = 0.0;
  for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) largest = std::max(largest, std::abs(eigen.eigenvalues()(k)));
  if (!std::isfinite(largest)) return;
  recent_[static_cast<std::size_t>(estimates_++ % recent_.size())] = std::min(largest, kMaxRate);
  rate_ = 0.0;
  for (std::size_t k = 0; k < std::min<std::size_t>(recent_.size(), static_cast<std::size_t>(estimates_)); ++k)
    rate_ = std::max(rate_, recent_[k]);
}

std::optional<double> ContractionEstimate::rate() const {
  if (pairs_ < window_) return std::nullopt;
  return rate_;
}

}  // namespace pushpull::deform::detail
