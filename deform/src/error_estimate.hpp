// Private: the solver's estimate of its distance to the exact minimiser, from the observed contraction of
// the plain local-global map G (one local step then one global step).
//
// G is a contraction near the minimiser x* with rate rho (the spectral radius of its Jacobian J). For any
// iterate x, however it was produced (plain or Anderson-accelerated):
//   |x - x*| <= |x - G(x)| + |G(x) - G(x*)| <= |r| + rho |x - x*|,  so  |x - x*| <= |r| / (1 - rho),
// with r = G(x) - x the plain step's residual, which every iteration computes anyway. rho is estimated from
// the secant pairs the iterations provide: with dX = [x_k - x_{k-1}, ...] and dG = [G(x_k) - G(x_{k-1}),
// ...] over a window, dG ~ J dX, and the eigenvalues of C = argmin |dX C - dG| (Ritz values of J on the
// span of the recent steps) approximate J's extreme eigenvalues; Anderson's steps span a Krylov-like space
// that holds exactly the slowly contracting modes that set rho. The largest |Ritz value| seen over the
// solve is kept (rho only matters near the end, and an early underestimate must not survive).
// The estimate is then rho_hat-scaled largest per-vertex residual; the benchmark checks it against
// references solved to 1e-9 for every method (deform_bench).
// Thread-safety: none; one per solve.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

namespace pushpull::deform::detail {

class ContractionEstimate {
 public:
  ContractionEstimate(int window, Eigen::Index dimension);
  // x: the iterate, g = G(x). Call once per iteration.
  void add(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g);
  // The estimated rate in [0, kMaxRate], once at least `window` secant pairs have been seen.
  [[nodiscard]] std::optional<double> rate() const;

  static constexpr double kMaxRate = 0.9999;

 private:
  int window_;
  int pairs_ = 0;  // secant pairs seen
  bool has_previous_ = false;
  Eigen::VectorXd previous_x_, previous_g_;
  Eigen::MatrixXd dX_, dG_;          // dimension by window, circular
  Eigen::MatrixXd xx_, xg_;          // window by window: dX^T dX, dX^T dG
  double rate_ = 0.0;                // largest |Ritz value| of the recent estimates
  std::array<double, 10> recent_{};  // the last few estimates, circular
  long estimates_ = 0;
};

}  // namespace pushpull::deform::detail
