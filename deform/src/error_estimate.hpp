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
// that holds exactly the slowly contracting modes that set rho. Three policies:
// - Recent (every method but those below): the largest |Ritz value| of the later half of the solve's
//   estimates (at least the last 10), clamped to kMaxRate, once `window` estimates have been made
//   (iteration 2 x window): the first Ritz values come from steps that have mostly seen the fast modes, and
//   an early underestimate must not survive. Stopping on the first one made 15 of 97 random pulls on the
//   shared models (small regions of the low-poly truck and car, fandisk, the hemisphere, the real car) stop
//   2.1-7.6x optimistic; waiting for a full window of estimates made it 9. The slow modes of asan's larger
//   regions come and go among the Ritz values (several rates within 1e-3 of 1): with only the last 10
//   estimates the hemisphere and the real car stopped 3-4x optimistic after 54-81 iterations while a rate
//   seen 10-15 iterations earlier would have held them; the later half holds it and still forgets the
//   first iterations' transients (the whole solve's largest cost the 10K height field 80 -> 122
//   iterations). The stops in the first iterations are checked by rate_probe.hpp.
// - Warm (Recent's methods, warm-started with a rate hint, which becomes the floor): the largest of the last
//   10 estimates, at least the floor. The hint is the rate of a nearby solve that ran past its transients
//   (or was probed), so it already holds the slow mode the later-half rule waits for. With the later half on
//   top, stopping_bench's hinted warm starts on the car's 2 m region took 188 / 66 / 27 iterations (asan,
//   from 0.9 / 0.97 / 0.995 d); with this rule 186 / 38 / 27 (186 / 24 / 23 since the rule on which Ritz
//   values count, below), every hinted row still honest (true distance at most 0.96x the estimate, on the 10K
//   height field; 0.49x on the car, 1.22x since the Ritz-value rule). Cold rows were unchanged by it. A hint
//   from a cold solve's first iterations is not settled (DeformResult::rate_settled) and gets Recent.
// - Cautious (per-triangle rotations: arap-m, arap-h, asan on arap-m): the largest of the whole solve,
//   clamped to kCautiousMaxRate, no rate before 10 estimates and none while one of the last 10 is >= 1. Their
//   soft fold modes contract at rates within 1e-4 of 1, and arap-h's non-convex energy has saddles where the
//   plain step's move falls to 1e-7 |d| and then grows again (Ritz values > 1): with the Recent rule arap-h
//   stopped on estimates 2.6-100x below its true distance (stopping_bench). Applying the >= 1 rule to every
//   method cost sr-arap its convergence (its Gauss-Seidel rotations give Ritz values >= 1 too), hence the two
//   policies.
// Which Ritz values count (Recent and Warm, when the local step fits every rotation exactly): the plain map's
// Jacobian is J = I - L^-1 H, with H the energy's Hessian and L the global matrix; the local step's surrogate
// lies above the energy and touches it with the same gradient, so H <= L (at every iterate where the energy
// is twice differentiable: each cluster's best rotation unique), and H >= 0 near a minimiser, so J's
// eigenvalues are real and in [0, 1]; at least the bound from above on the spectrum of L^-1 H, the one used
// here, holds at every iterate. sr-arap's Gauss-Seidel sweeps are no exact fit (J is not even self-adjoint
// there): it counts every value, as before. A window whose values are all left out is no estimate. Ritz
// values with a non-positive real part are the secant model's noise (Anderson's mixed steps, the rotations'
// nonlinearity: -5.7, -2.7, -1.3 between slow-mode values of 0.998-0.9994 on deform_bench's 30K field, asan)
// and are left out: taken as |value| and clamped to kMaxRate, each held an estimate of 1e4 |r| over the later
// half of the solve, and the 30K field stopped after 154 iterations at a true distance of 2.9e-4 |d| (now 128
// at 4.0e-3, estimate 5.2e-3). Values of modulus >= 1 (J's spectrum ends at 1) are left out too since
// 2026-12-06: until then they stayed, clamped to kMaxRate, because leaving them out had made one real-car
// pull stop 2.10x optimistic after 215 iterations (keeping them took 566); that slow mode was most likely a
// whole part's translation, which a solve now starts at (deformer_impl.hpp). Kept, they held the car's nose
// (stopping_bench) at the 0.9999 clamp from iteration 80 while a 40-step rate probe forced every 40
// iterations (an ad-hoc driver, not kept) read a steady 0.99764:
// the stop came 15x pessimistic after 159 and 155 iterations (1 m, 2 m); left out, after 129 and 126 (true
// distance 0.29 and 0.41 of the estimate). On the eighteen seeds of random pulls (asan and arap-sr) 62,468
// iterations and 44,280 probe steps against 64,911 and 43,419, on six new seeds (20261207, 515151, 8675309,
// 1234567, 42, 271828) 18,720 and 15,416 against 19,209 and 15,088, none more than 1.32x optimistic either
// way; arap-s, arap-n and arap-sr-h (seed 777001) honest. On the random pulls of the README's twelve seeds
// (1,126 solves then) (stopping_bench): 69,892 iterations and 32,759 probe steps before, 68,404 and 33,333
// after (at 183d9c2, and the same at 4c51571, with sr-arap's exemption and the empty-window rule), the
// largest true / estimate 1.97 both times (since asan's Anderson waits for a full window, anderson.hpp:
// 61,900 iterations, 36,408 probe steps, largest 1.55); the fixed problems' rows are unchanged but for asan
// on the hemisphere (40 -> 25 iterations, ratio 0.15) and the car's warm starts (2 m region, unhinted 188 /
// 66 / 16 -> 154 / 24 / 23 iterations, hinted 186 / 38 / 27 -> 186 / 24 / 23; true / estimate at most 1.40,
// where it was at most 0.38). sr-arap's rows are bit-identical. Cautious keeps every value, its rule
// unchanged: it takes any recent value of modulus >= 1 as iterates moving away. The estimate is then
// rho_hat-scaled largest per-vertex residual; the benchmark checks it against references solved to 1e-9 for
// every method (deform_bench). Thread-safety: none; one per solve.
#pragma once

#include <Eigen/Core>
#include <array>
#include <deque>
#include <optional>
#include <utility>

#include "helper_thread.hpp"
#include "secant_history.hpp"

namespace pushpull::deform::detail {

class ContractionEstimate {
 public:
  enum class Policy { Recent, Warm, Cautious };
  // exact_local_fit: whether the local step fits every rotation exactly (every method but sr-arap, whose
  // Gauss-Seidel sweeps do not); only then are Ritz values with a non-positive real part or a modulus >= 1
  // left out.
  ContractionEstimate(int window, Eigen::Index dimension, Policy policy = Policy::Recent,
                      bool exact_local_fit = true);
  // Call once per iteration, after history.add(x, g) (x the iterate, g = G(x)); the history's window must be
  // at least this one. Reads the Gram entries of the newest `window` pairs (secant_history.hpp).
  void add(const SecantHistory& history);
  // Standalone: records (x, g) in a history of its own (the same sums with or without `threads`), then the
  // above.
  void add(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g,
           HelperThread* threads = nullptr);
  // The estimated rate in [0, kMaxRate] (Cautious: [0, kCautiousMaxRate]), once `window` estimates have been
  // made (Cautious: 10); before that, with a floor (Recent and Warm), the floor or the estimates so far if
  // larger. Cautious: empty while a recent Ritz value says the iterates move away (>= 1).
  [[nodiscard]] std::optional<double> rate() const;
  // A lower bound for the rate from an earlier solve of a nearby problem (a warm start's): rate() is at
  // least this, and (Recent and Warm) available from the first iteration on. Clamped to the policy's maximum.
  void set_floor(double rate);
  // Recent and Warm: the largest rate of the last 10 estimates (and at least the floor), the rate to hand to
  // a warm start from this iterate (DeformResult::contraction_rate). rate() may be larger: it keeps a slow
  // mode the later half of the solve has seen. Passing rate() instead cost the warm starts of stopping_bench
  // 4x the iterations (10K height field, 0.995 d: 12 -> 51) with no row more honest. Cautious: rate().
  [[nodiscard]] std::optional<double> recent_rate() const;

  static constexpr double kMaxRate = 0.9999;
  static constexpr double kCautiousMaxRate = 0.99999;

 private:
  int window_;
  Policy policy_;
  bool contracting_only_;  // leave out Ritz values with a non-positive real part or a modulus >= 1
  Eigen::Index dimension_;
  long pairs_ = 0;                    // secant pairs seen
  std::optional<SecantHistory> own_;  // the standalone add's
  double rate_ = 0.0;  // largest |Ritz value| of the later half (Warm: the last 10; Cautious: the solve)
  double recent_only_ = 0.0;         // Recent and Warm: the last 10 estimates' largest, clamped
  double whole_solve_ = 0.0;         // largest |Ritz value| of the whole solve (Cautious)
  bool expanding_ = false;           // a recent |Ritz value| >= 1
  std::array<double, 10> recent_{};  // the last few estimates (unclamped), circular
  std::deque<std::pair<long, double>> later_;  // Recent: the later half's maximum (index, estimate)
  long estimates_ = 0;
  std::optional<double> floor_;
};

}  // namespace pushpull::deform::detail
