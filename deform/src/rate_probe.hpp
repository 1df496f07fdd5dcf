// Private: an independent check of the local-global map's contraction rate, made once at an early candidate
// stop (local_global.cpp says when).
//
// Why: the running estimate (error_estimate.hpp) takes Ritz values from the iterates' differences. A mode
// that contracts at rate lambda appears there weighted by 1 - lambda, so a slow mode (lambda ~ 0.999, a
// nearly free hinge or a soft direction of asan's material) stays invisible until the fast modes have died
// out, and a solve that stops early can stop with most of its error in that mode: on the shared models 7-10%
// of random pulls stopped 2-6.4x optimistic (stopping_bench --random-pulls), nearly all within 32
// iterations, and on later seeds cold solves of the real car stopping at 33-36 iterations up to 21.8x.
//
// How: `steps` Arnoldi steps on the Jacobian J of the plain map G, from a fixed pseudo-random start vector
// (which holds every mode, the slow ones included, with weight ~1/sqrt(n)) plus, when the caller gives one, a
// hint (the solve's last plain step: where the iterates stall, that step lies along the slow mode that holds
// them; each scaled to unit M norm), orthogonalised in the inner
// product of `metric` (the prefactored matrix Q_ff: J = I - Q_ff^-1 H is self-adjoint in it, so the
// projected matrix is close to symmetric and its Ritz values approach J's extreme eigenvalues from inside).
// The caller supplies J v (a finite difference of G, one local and one global step per call). The largest
// |Ritz value| is a lower bound on the spectral radius; the solver sets a floor under its running estimate
// from it (its distance to 1 halved, local_global.cpp). On the random pulls 20 steps found every slow mode
// that 8-16 steps missed; on later seeds 40 (with the gap to 1 halved, local_global.cpp) held stops that 20
// let through 2-6x optimistic. On the ToyCar's front corner (asan, 2,590 region vertices) the iterates
// stalled 0.019 |d| from the minimiser in a mode of rate 0.9995 that 40 steps from the random start missed
// (0.99728; 80 steps found it): the solve stopped 2.9x optimistic. From the random start plus the last step,
// 40 find it.
//
// The Ritz values approach the spectrum from inside only where J is self-adjoint in M: sr-arap's Gauss-Seidel
// sweeps and arap-h's saddles are not, and finite differences are noisy next to 1, so the solver's floor
// from the probe stops at kProbeMaxRate (local_global.cpp).
// Where J is self-adjoint in M (the exact local fits: arap-s, arap-sr, arap-n, asan on arap-sr), the
// projected matrix is, up to rounding and the finite differences' noise, symmetric tridiagonal, and the
// Lanczos recurrence (probe_rate_self_adjoint) builds it from the last two basis vectors alone: same Ritz
// values, without the Gram-Schmidt passes against the whole basis. On stopping_bench's problems and a seed
// of random pulls (103 probes, 24-9,400 free vertices, asan, arap-sr, arap-n, arap-s) its largest Ritz value
// agreed with Arnoldi's to 1e-7 in every probe, in 50-70% of its time (scratch comparison, 2026-12-07).
// Memory: Arnoldi keeps `steps` vectors of `dimension` doubles (40 x 3 n_free: 96 MB on a 100K region),
// Lanczos six.
// Deterministic: the start vector is a fixed function of the dimension (splitmix64), the same on every
// platform. Thread-safety: reentrant (no state outside its arguments and callbacks).
#pragma once

#include <Eigen/Core>
#include <functional>

#include "helper_thread.hpp"

namespace pushpull::deform::detail {

struct RateProbe {
  double rate = 0.0;       // largest |Ritz value| found (0 when nothing could be probed)
  int evaluations = 0;     // completed calls of `jacobian`
  bool abandoned = false;  // `jacobian` returned false (the solve was cancelled): rate is 0
};

// jacobian(v, out): out = J v; returns false to abandon the probe. metric(v, out): out = M v for a symmetric
// positive definite M. Both get and fill vectors of `dimension`. Stops early when the Krylov space is
// exhausted (an invariant subspace) or a product is not finite. `threads`, when given, runs the
// orthogonalisation against the basis (half of each step's time at 10K vertices: it reads the basis four
// times) in two fixed halves of the rows, the same bits either way; not to be called from inside a job of it.
[[nodiscard]] RateProbe probe_rate(
    Eigen::Index dimension, int steps,
    const std::function<bool(const Eigen::VectorXd& v, Eigen::VectorXd& out)>& jacobian,
    const std::function<void(const Eigen::VectorXd& v, Eigen::VectorXd& out)>& metric,
    HelperThread* threads = nullptr, const Eigen::VectorXd* hint = nullptr);

// The same probe by the Lanczos recurrence in the M inner product, for a J self-adjoint in M: each step
// orthogonalises J v against the last two basis vectors (twice) instead of the whole basis, and one metric
// product per step gives both the new vector's norm and its M image. The largest |eigenvalue| of the
// tridiagonal matrix is the rate. Where orthogonality is lost (after a Ritz value has converged) the
// tridiagonal matrix repeats converged eigenvalues, which leaves the largest one. On a J that is not
// self-adjoint in M it reads a different rate than Arnoldi (arap-sr-h: 0.99986 against 0.99979); use
// probe_rate there. Single-threaded, deterministic; same stops and results as probe_rate otherwise.
[[nodiscard]] RateProbe probe_rate_self_adjoint(
    Eigen::Index dimension, int steps,
    const std::function<bool(const Eigen::VectorXd& v, Eigen::VectorXd& out)>& jacobian,
    const std::function<void(const Eigen::VectorXd& v, Eigen::VectorXd& out)>& metric,
    const Eigen::VectorXd* hint = nullptr);

// The fixed start vector (unit in the Euclidean norm): entries uniform in [-0.5, 0.5) from splitmix64.
[[nodiscard]] Eigen::VectorXd probe_start(Eigen::Index dimension);

}  // namespace pushpull::deform::detail
