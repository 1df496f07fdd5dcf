// pushpull::deform::Deformer: the local-global solver for the ARAP family and ASAN.
//
// Usage (precompute once per region, solve many times, e.g. for every drag update):
//   auto mesh = std::make_shared<const Mesh>(load(...));
//   Deformer deformer(mesh, build_roi(*mesh, handle, fixed), DeformOptions{.method = Method::Asan});
//   DeformResult r = deformer.solve(Eigen::Vector3d(0, 0, 0.1));   // handle moves by d = (0, 0, 0.1)
// or the one-shot deform(mesh, roi, d, options).
//
// Energies (p rest positions, p' deformed, e_ij = p_i - p_j, w_ij cotangent weights):
// - arap-s (Sorkine & Alexa 2007, "As-rigid-as-possible surface modeling"): one cluster per vertex k
//   with its spokes (k,j), w_kj = (cot a_kj + cot b_kj)/2.
//   E = sum_k min_R_k sum_j w_kj |e'_kj - R_k e_kj|^2.
// - arap-sr (Chao et al. 2010, "A simple geometric model for elastic deformations"): cluster k = the
//   three edges of every triangle around k (spokes and rims), each with the half weight
//   cot(opposite angle)/2 of that triangle.
// - arap-m (Zhao et al.; per-triangle ARAP as in Liu et al. 2008): one cluster per triangle t, its three
//   edges with cot(opposite angle)/2. E = sum_t min_R_t sum_{(i,j) in t} (cot a_ij/2) |e'_ij - R_t e_ij|^2.
// - arap-n (Chen et al. 2017, "Rigidity controllable as-rigid-as-possible shape deformation"):
//   cluster k = the edges of every triangle incident to a vertex at most n-1 rings from k (n = 1 is
//   arap-sr), half cotangent weights.
// - sr-arap (Levi & Gotsman 2014, "Smooth rotation enhanced as-rigid-as-possible mesh animation"):
//   E = E_arap-sr + alpha A sum_{edges (k,l)} |w_kl| ||R_k - R_l||_F^2, A = total area of Omega.
//   Local step: three Gauss-Seidel sweeps R_k = polar(S_k + alpha A sum_l |w_kl| R_l) (with one, the error
//   estimate ran up to 8.8x optimistic: local_global.cpp); global step unchanged.
// - arap-h (Zhao et al.'s hybrid as Le Vaou et al. 2020, section 3.3, describe it: "ARAP-m plus an energy
//   term on the variation of the discrete mean curvature, weighted linearly"):
//   E = E_arap-m + lambda sum_i A_i min_{R_i in SO(3)} |H'_i - R_i H_i|^2,
//   H = M^-1 L p the mean-curvature normal at rest, H' = M^-1 L p' its linearisation at the deformed
//   positions (L the cotangent Laplacian of the rest Omega, M the lumped barycentric areas A_i = area of the
//   incident faces / 3, both fixed, so the term is quadratic in p' for fixed R_i), summed over the Omega
//   vertices whose whole one-ring is in Omega and off the mesh border; lambda = arap_h_lambda * mean(A_i).
//   Each bending vertex has its own rotation R_i, fitted in the local step next to the per-triangle
//   rotations of arap-m: the term's covariance (L p')_i H_i^T has rank one, so R_i is any rotation turning
//   H_i onto (L p')_i (the solver takes the smallest) and the term equals lambda A_i (|H'_i| - |H_i|)^2:
//   invariant to rigid motions, it penalises the change of the mean curvature's magnitude. Vertices with
//   H_i = 0 keep lambda A_i |H'_i|^2. Global matrix L_w + lambda L^T M^-1 L (SPD, prefactored); lambda = 0
//   is arap-m. Zhao et al. weigh the terms as (1 - w) E_m + w E_b, the same minimiser as lambda = w / (1 - w)
//   here (the option arap_h_lambda = lambda / mean(A_i) is free of units).
// - arap-sr-h (this project's earlier arap-h, kept for comparison): the same bending term on the arap-sr
//   structure, with R_i the arap-sr rotation of vertex i's cluster instead of a rotation of its own:
//   E = E_arap-sr + lambda sum_i A_i |H'_i - R_i H_i|^2, R_i shared with the membrane term of cluster i.
// - asan (Le Vaou et al. 2020, CAD 121, sections 4.2 and 4.4): stretch a copy of Omega,
//   tau(p) = p + (mu - 1) (p . d_o) / |d_o|^2 d_o, take the half cotangents of the stretched triangles and
//   use them as the weights of arap-sr (asan_base = ArapSR, the paper's choice) or arap-m on the real
//   mesh. d_o defaults to the push/pull direction d; mu defaults to 100.
// Weights: every half cotangent comes from intrinsically mollified edge lengths (Sharp & Crane 2020, "A
// Laplacian for nonmanifold triangle meshes", section 4.5): the smallest length that makes every triangle of
// the region satisfy the triangle inequality by eps = 1e-4 x the region's mean edge length is added to all
// its edges, and each triangle's three cotangents are those of that valid triangle. Each triangle's
// stiffness is then positive semidefinite by construction, so the global matrix is positive definite and
// the energy never negative for arap-sr, arap-m, arap-n, sr-arap, arap-h, arap-sr-h and asan on any input
// (slivers, needles, caps); sliver weights stay bounded (|cot| <~ longest edge / eps); well-shaped triangles
// change by at most eps / edge length (nothing changes when no triangle needs it). Clamping each cotangent,
// as before, broke cot a cot b + cot b cot c + cot c cot a = 1 and made the matrix indefinite on slivers.
// asan mollifies the stretched copy with the same eps (relative to the rest mesh; cotangent.hpp says why).
// arap-s: its global matrix is twice the cotangent Laplacian, positive definite too, but its per-vertex
// spoke energies can have negative weights (the paper's Fig. 3), so its energy can be negative: solve
// throws (method, region size, what to try) when it ends negative instead of returning a meaningless shape.
// Zero-area faces (twice area <= 1e-14 longest edge^2) are left out of the region. If a factorization
// still fails, the std::runtime_error names the method, the region's size and what to try.
//
// Solver: rest positions with the handle (and fixed vertices) moved to their targets as initial guess (or a
// given one; the paper does not state its own); each iteration = covariances, 3x3 rotations (Newton on SO(3)
// warm-started from the previous iteration, SVD fallback; det R = +1), one sparse scatter, one prefactored
// sparse LDL^T solve with the 3 coordinates in one pass, and the energy. Symbolic analysis happens once per
// Deformer; the numeric factorization is redone only when the weights change (asan: when the line of d_o
// changes; d_o and -d_o give the same weights). Every solve starts from identity rotations, so equal requests
// give bit-identical results (replay).
//
// Units: model units (metres for glTF). Frame: model space. Shapes stated at each member.
// Ownership: the Deformer shares the rest mesh (shared_ptr<const Mesh>) and owns everything else.
// Thread-safety: a Deformer may be moved to and used from any one thread at a time; const members are safe
// to call concurrently. The progress callback runs on the solving thread. With DeformOptions::threads = 1 a
// solve uses the calling thread only (deform::Service runs it so on its worker); otherwise regions with more
// than ~20K cluster terms split the local step and the triangular solves with one helper thread, with
// bit-identical results.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/mesh_validation.hpp"
#include "pushpull/deform/method.hpp"
#include "pushpull/deform/roi.hpp"

namespace pushpull::deform {

enum class StopReason {
  ErrorTolerance,   // estimated largest vertex distance to the minimiser <= tolerance * reference length
  EnergyTolerance,  // relative energy change in the last iteration <= energy_tolerance
  MaxIterations,    // max_iterations reached without meeting a tolerance
  Cancelled,        // the progress callback returned false
};

[[nodiscard]] std::string_view stop_reason_name(StopReason reason);

// Passed to the progress callback after every iteration.
struct IterationReport {
  int iteration = 0;      // 1-based; 0 only with probe_step > 0, during a coarse-to-fine start's coarse solve
  double energy = 0.0;    // energy of the current positions (model units^2)
  double max_move = 0.0;  // largest vertex move of this iteration's plain step / reference length
  // Estimated largest vertex distance of these positions to the exact minimiser / reference length (see
  // DeformOptions::tolerance); empty for the first few iterations, until the contraction rate is known, and
  // while the iterates move away from a fixed point (a saddle of a non-convex energy such as arap-h's).
  std::optional<double> error_estimate;
  // The contraction rate to carry to a warm start from these positions (see DeformResult::contraction_rate);
  // whether it is settled: rate_settled below.
  std::optional<double> contraction_rate;
  // #V by 3 full-mesh positions after this iteration: an immutable copy the receiver may keep (e.g. publish
  // as a preview snapshot to another thread). Never null.
  std::shared_ptr<const Eigen::MatrixXd> V;
  // 0 for an iteration. k > 0: the rate probe's k-th step after this iteration (DeformResult::probe_rate),
  // with the iteration's fields again (max_move 0), or, with iteration 0, the k-th evaluation of a
  // coarse-to-fine start's coarse solve (DeformOptions::coarse_start_min_free; V the positions before it,
  // energy 0 and no estimate): nothing new to show; answer only whether to go on.
  int probe_step = 0;
  // Whether contraction_rate is settled (DeformResult::rate_settled); pass both on (ConstraintTargets).
  bool rate_settled = false;
};

// Called on the solving thread after every iteration; return false to stop the solve at this iteration
// boundary (the result then has cancelled = true and holds this iteration's positions).
using ProgressCallback = std::function<bool(const IterationReport&)>;

struct DeformOptions {
  Method method = Method::Asan;
  // asan: stretch factor of tau (> 1; the paper uses 100).
  double mu = 100.0;
  // asan: the apparent orthotropy direction d_o; default = the push/pull direction d (the paper's choice).
  std::optional<Eigen::Vector3d> stretch_direction;
  // asan: the energy the anisotropic weights go into: Method::ArapSR (paper's ASAN) or Method::ArapM.
  Method asan_base = Method::ArapSR;
  // Iteration cap. The paper runs 50 plain iterations (anderson_window = 0, tolerance = 0: see
  // paper_iterations()); the default lets the stopping rule decide.
  int max_iterations = 1000;
  // Accuracy: stop when the estimated largest vertex distance to the exact minimiser <= tolerance *
  // reference length, where reference length = the largest prescribed displacement |d| (or the region's
  // bounding-box diagonal if nothing moves). Default 1e-2: 1 mm on a 100 mm pull. The estimate is
  // |r| / (1 - rho): r the plain local-global step's largest vertex move, rho the contraction rate of that
  // step estimated from the iterates (Ritz values over a window of secant pairs; src/error_estimate.hpp);
  // deform_bench checks it against references solved to 1e-9 for every method. 0 = off. Per-triangle
  // rotations (arap-m, arap-h, asan on arap-m) use a cautious rate (the largest of the solve, none while the
  // iterates move away from a saddle), so they often run to max_iterations unconverged rather than claim an
  // accuracy they do not have (stopping_bench).
  double tolerance = 1e-2;
  // Also stop when |E_k - E_{k-1}| <= energy_tolerance * E_{k-1}. 0 = off (the default: a small energy change
  // says little about the distance to the minimiser on stiff problems).
  double energy_tolerance = 0.0;
  // Anderson acceleration (Peng et al. 2018) of the local-global fixed point with this many previous
  // iterates; 0 = off (the paper's plain iterations). Falls back to the plain step whenever the accelerated
  // iterate raises the energy, so the energy trace never rises. On by default: it reaches the same shape
  // in 5-10x fewer iterations (asan on a 10K height field: 16 instead of 117 to 1e-3 |d|, when measured
  // before asan waited for a full window). asan extrapolates only once the window holds this many iterates'
  // differences (plain steps until then, at the start and after each rejected step; deform/src/anderson.hpp
  // says why), so a larger window also means more plain steps for asan.
  int anderson_window = 5;
  // An asan cold solve (no initial guess) of a region with at least this many free vertices starts from the
  // constrained vertices' displacements spread biharmonically over the region (uniform graph Laplacian;
  // deform/src/smooth_start.hpp) instead of from the rest positions with only the constrained vertices
  // moved, whose first global step is a membrane-like cone the iterations then spend tens of steps rounding.
  // Same minimiser, same stopping rule. Measured (deform_bench, 2 threads, 2026-12-05): the 100K height field
  // in 143 iterations and 4.8 s instead of 281 and 9.5 s (its factorization 606 ms instead of 268: L_ff is
  // factored once per region), the 30K one in 89 instead of 128, even in time (1.14 s, 1.19 s). Smaller
  // regions stop within the rate probe's window (deformer.hpp: DeformResult::probe_rate), whose 40 steps eat
  // the gain: the 10K field took 54 iterations and 357 ms instead of 85 and 170 (stopping_bench
  // --smooth-start-min-free 0). asan only: arap-sr's estimate ran 3.1x optimistic from it (30K field: 3.0e-2
  // |d| from the reference solved from rest, estimate 9.6e-3; 1.1e-2 from rest); whether it found another
  // local minimum there was not checked. -1: never (paper_iterations() uses it: the paper's iterations start
  // from rest); 0: every asan cold solve.
  int smooth_start_min_free = 25000;
  // An asan cold solve (no initial guess, tolerance > 0) of a region with at least this many free vertices
  // starts coarse-to-fine: the same push/pull is solved first on a coarser tessellation of the region (about
  // a ninth of its free vertices, every constrained vertex kept; a coarse region still over this size
  // coarsens again), the coarse shape is carried to the region, and the fine iterations start from there
  // (deform/src/coarse_start.hpp). It takes the smooth start's place. It saves fine iterations, but a fine
  // solve that then stops within the rate probe's window pays the probe's 40 evaluations: deform_bench on
  // 2026-12-06 (2 threads, against the start the region gets without it, in the same run) measured 10K 44
  // iterations and 228 ms against 85 and 114 from rest, 30K 57 and 896 ms against 89 and 667 smooth, 50K 71
  // and 1,555 ms against 98 and 1,130 smooth; past the probe's window it pays: 60K 93 and 1,178 ms against
  // 114 and 1,581, 75K 94 and 1,640 against 122 and 3,004, 100K 91 and 2,124 against 152 and 3,922. Regions
  // whose tessellation barely coarsens (small patches with few interior vertices) start as without. -1:
  // never (paper_iterations() uses it).
  int coarse_start_min_free = 60000;
  int arap_n_rings = 2;         // arap-n: n >= 1
  double sr_arap_alpha = 0.02;  // sr-arap: alpha >= 0 (dimensionless)
  double arap_h_lambda = 1.0;   // arap-h, arap-sr-h: lambda / mean vertex area (dimensionless), >= 0
  // Validate the mesh in the constructor (throws MeshValidationError); turning it off skips O(F log F) work.
  bool validate = true;
  // Threads a solve may use: 0 = automatic (one helper thread on large regions; a coarse-to-fine start's
  // coarse Deformer may keep one of its own), 1 = the calling thread only. Results are bit-identical either
  // way.
  int threads = 0;
  // Default progress callback of every solve (a per-solve one given to solve() takes precedence).
  ProgressCallback progress;
};

struct TimingMs {
  double precompute = 0.0;     // constructor: validation, clusters, right-hand-side map, symbolic analysis
  double factorize = 0.0;      // this solve: weights + numeric factorization (0 when reused), and at a
                               // region's first cold solve the smooth start's factorization or the
                               // coarse-to-fine start's coarser region and its Deformer
  double solve = 0.0;          // this solve: all iterations, the rate probe's evaluations if any, the
                               // smooth start's spread or the coarse-to-fine start's coarse solve
  double per_iteration = 0.0;  // solve without the starts' spread or coarse solve / (iterations +
                               // DeformResult::probe_evaluations)
};

struct DeformResult {
  Eigen::MatrixXd V;  // #V by 3 deformed positions of the full mesh (Outside vertices unchanged)
  int iterations = 0;
  // stop_reason is ErrorTolerance, or EnergyTolerance with error_estimate <= DeformOptions::tolerance
  bool converged = false;
  // Estimated largest vertex distance to the exact minimiser / reference length, at the last iteration.
  std::optional<double> error_estimate;
  // The contraction rate of the plain local-global step over the last iterations (in [0, 1); empty until
  // known; at least min(1 - (1 - probe_rate) / 2, 0.999) when the probe ran). Pass it as
  // ConstraintTargets::rate_hint, and rate_settled as rate_hint_settled, when this result warm-starts a
  // nearby solve.
  std::optional<double> contraction_rate;
  // Whether contraction_rate has seen what a cold solve's first iterations cannot: true once the rate probe
  // has run, once the solve is past the probe's window (32 iterations, asan 80), or from the start in a
  // warm start whose hint was settled. A drag's request superseded in its first iterations hands on an
  // unsettled rate.
  bool rate_settled = false;
  // The rate behind error_estimate: the largest of the later half of the solve (a warm start with a
  // rate_hint: of its last 10 estimates), at least the hint and the probe's floor
  // (deform/src/error_estimate.hpp says why it may exceed contraction_rate).
  std::optional<double> estimate_rate;
  // A solve that reaches its tolerance within its first 32 iterations (asan: 80; on a region of at most 8,000
  // free vertices at any iteration) without a rate_hint (a cold solve, or a warm start that brings no rate)
  // first checks the rate its estimate rests on: 40 Lanczos or Arnoldi steps
  // on the local-global map's Jacobian from a fixed random start, each one extra local and global step. A
  // slower rate found there (its distance to 1 halved, taken up to 0.999) raises the estimate, and the solve
  // goes on. probe_rate: the largest rate the probe found (empty: no probe); probe_evaluations: its
  // local-global steps (not in `iterations`; their time is in timing.solve).
  std::optional<double> probe_rate;
  int probe_evaluations = 0;
  bool cancelled = false;
  StopReason stop_reason = StopReason::MaxIterations;
  std::vector<double> energy_trace;  // energy after every iteration (size == iterations)
  double initial_energy = 0.0;       // energy of the initial guess
  // This solve computed weights and a numeric factorization (the first solve; asan when the line of d_o
  // changed); false when it reused the previous ones.
  bool refactored = false;
  // This cold solve started from the biharmonic spread (DeformOptions::smooth_start_min_free).
  bool smooth_start = false;
  // This cold solve started coarse-to-fine (DeformOptions::coarse_start_min_free); coarse_evaluations: the
  // local-global evaluations of its coarse solve (coarser levels and rate probe included; also those of a
  // coarse solve the progress callback stopped), each on a ninth of the region or less; not in
  // `iterations`, their time in timing.solve but not in per_iteration.
  bool coarse_start = false;
  int coarse_evaluations = 0;
  TimingMs timing;
  std::vector<std::string> warnings;  // validation, region and solver warnings
};

// General boundary conditions: targets for the handle (and optionally the fixed) vertices.
struct ConstraintTargets {
  Eigen::MatrixXd handle_positions;  // #handle by 3, row k = target of roi.handle[k]
  Eigen::MatrixXd
      fixed_positions;  // empty = rest positions, else #fixed by 3, row k = target of roi.fixed[k]
  // asan: the push/pull direction d that sets d_o when DeformOptions::stretch_direction is unset; default =
  // mean handle displacement.
  std::optional<Eigen::Vector3d> push_direction;
  // empty = a cold start: rest positions with constrained vertices at targets (large regions: the targets'
  // biharmonic spread, DeformOptions::smooth_start_min_free, or the largest a coarse solve carried over,
  // coarse_start_min_free); else #V by 3
  Eigen::MatrixXd initial_guess;
  // With a warm start: the contraction rate of the solve the initial guess came from
  // (DeformResult::contraction_rate). A warm start begins close to the minimiser, so its first iterations
  // see too little of the slowly contracting modes to estimate the rate, and the estimate of a few
  // iterations was up to 2.9x optimistic (asan, 10K, a drag's next request 1% longer). The error estimate
  // uses the larger of this rate and its own, and may use this one before its own is known. In [0, 1).
  std::optional<double> rate_hint;
  // Whether rate_hint is settled (DeformResult::rate_settled). A settled hint carries the slow modes, and
  // the estimate reads its own last 10 Ritz values above it; an unsettled one (a solve's first iterations)
  // is only a floor under the largest of the later half of the solve, as in a cold solve.
  bool rate_hint_settled = true;
};

class Deformer {
 public:
  // Validates the mesh (unless options.validate is false), builds clusters and the symbolic factorization.
  // Throws std::invalid_argument (MeshValidationError for the mesh) naming what is wrong: roi.role size !=
  // #V, no handle, bad options (mu <= 1, arap_n_rings < 1, negative alpha/lambda/window/tolerance, asan_base
  // not ArapSR/ArapM). A component of Omega without handle or fixed vertex is pinned at rest (warning).
  Deformer(std::shared_ptr<const Mesh> rest, RegionOfInterest roi, const DeformOptions& options = {});
  ~Deformer();
  Deformer(Deformer&&) noexcept;
  Deformer& operator=(Deformer&&) noexcept;
  Deformer(const Deformer&) = delete;
  Deformer& operator=(const Deformer&) = delete;

  // Push/pull: every handle vertex moves by d (model units), fixed vertices stay at rest. `progress`, when
  // set, replaces DeformOptions::progress for this solve.
  // Throws std::runtime_error naming the method, the region's size and what to try when the global matrix
  // cannot be factored, or when arap-s ends with a negative energy (its negative spoke weights dominate).
  [[nodiscard]] DeformResult solve(const Eigen::Vector3d& d, const ProgressCallback& progress = {});
  // General targets (e.g. a rigid transform of the handle as in the cactus benchmark, or a push/pull with a
  // warm start). Throws std::invalid_argument when shapes do not match or a value is not finite.
  [[nodiscard]] DeformResult solve(const ConstraintTargets& targets, const ProgressCallback& progress = {});
  // The targets solve(d) uses: handle vertices at rest + d, push_direction = d, no initial guess.
  [[nodiscard]] ConstraintTargets push_pull_targets(const Eigen::Vector3d& d) const;
  // The rest mesh this Deformer was built on.
  [[nodiscard]] const std::shared_ptr<const Mesh>& rest_mesh() const;

  [[nodiscard]] const RegionOfInterest& roi() const;
  [[nodiscard]] const DeformOptions& options() const;
  [[nodiscard]] const ValidationReport& validation() const;
  // The energy (model units^2) of the given #V by 3 positions under the current weights (ASAN: those of the
  // last solve), minimised over the rotations (sr-arap: 20 Gauss-Seidel sweeps from the uncoupled optimum).
  [[nodiscard]] double energy(const Eigen::MatrixXd& V) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The paper's setting: `base` with 50 plain local-global iterations (no Anderson acceleration, no stopping
// rule). Not converged in general: results carry the error estimate so the gap is visible.
[[nodiscard]] DeformOptions paper_iterations(DeformOptions base = {});

// One-shot convenience: Deformer(mesh copy, roi, options).solve(d).
[[nodiscard]] DeformResult deform(const Mesh& mesh, const RegionOfInterest& roi, const Eigen::Vector3d& d,
                                  const DeformOptions& options = {});

}  // namespace pushpull::deform
