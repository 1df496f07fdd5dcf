// deform_bench: how fast arap-sr and asan reach the default accuracy on 10K / 30K / 100K-vertex regions,
// next to CGAL's Surface_mesh_deformation (SPOKES_AND_RIMS, the arap-sr energy) on the same problem.
//
// Problem: make_height_field(n) (n^2 vertices, all in the region; disk handle at the centre pulled by
// d = (0, 0, 0.1); outer ring fixed). Accuracy is measured, never assumed: every run's result is compared
// with a reference of the same energy solved to an estimated 1e-9 |d| ("err/|d|" = largest vertex distance
// to it over |d|). Our solver stops on its own error estimate (default 1e-2 |d|); CGAL runs until it is at
// least as close to the reference as our single-threaded arap-sr result, so the ratio compares equal
// accuracy, equal energy and equal thread count (one). Times are wall-clock milliseconds;
// per-iter is the median of 5 solves of 20 iterations each with the factorization in place.
//
// arap-sr at 100K stops unconverged at the 1000-iteration cap (1000*), and says so. Measured on 2026-12-03:
// the height field's dimple at (0.2, 0.7) snaps through. Its depth (centre height minus the mean over the
// ring 0.08-0.12 around it) is -0.0073 at rest; after 1000 accelerated iterations it is +0.0053 (inverted;
// the centre moved 0.085) at energy 1.35116e-3, while 1000 plain iterations (no Anderson) keep it at -0.0095
// at the higher energy 1.36372e-3. Buckling is nearly isometric, so the energy falls very slowly along it.
// The 10K and 30K fields keep the dimple (-0.0050 after 37 iterations, -0.0069 after 108), and so does asan,
// stiff across d, at 100K (-0.0064, converged after 229).
//
// Usage: deform_bench [--quick] [--no-peer] [--no-reference] [--side N]... [--method arap-sr|asan]
//                     [--coarse-start-min-free N]
//   --quick: the 10K problem only, for CI smoke runs; --no-peer: skip the CGAL rows, which take minutes at
//   100K, when comparing our own changes; --side N: an N x N problem instead of the default sizes
//   (repeatable; 100, 173, 316 are the 10K, 30K, 100K rows the targets read); --no-reference: skip the
//   tightly converged reference (minutes at 100K), err/|d| prints nan: for timing comparisons only;
//   --method: that method's rows only (both by default); --coarse-start-min-free: DeformOptions'
//   threshold for the coarse-to-fine start (its rows then compare with the same solve without it).
#include "height_field.hpp"

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"

#ifdef PUSHPULL_BENCH_WITH_CGAL
#include "cgal_peer.hpp"
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace pd = pushpull::deform;
namespace pb = pushpull::bench;

namespace {

constexpr int kTimedIterations = 20;  // for the per-iteration figure: the median of kTimedSolves solves
constexpr int kTimedSolves = 5;       // of kTimedIterations each (one solve is noisy on a shared machine)

struct OurRun {
  double precompute_ms = 0.0;
  double factorize_ms = 0.0;
  double per_iteration_ms = 0.0;
  double converge_ms = 0.0;  // factorize + iterations to the stopping rule (precompute: once per region)
  int iterations = 0;
  int probe_evaluations = 0;  // the rate probe's local-global steps (DeformResult::probe_evaluations)
  bool converged = false;
  // The solve started from the biharmonic spread (DeformOptions::smooth_start_min_free).
  bool smooth_start = false;
  // The solve started coarse-to-fine (DeformOptions::coarse_start_min_free); its coarse solve's evaluations.
  bool coarse_start = false;
  int coarse_evaluations = 0;
  double estimate = 0.0;  // the solver's own error estimate / |d|
  double error = 0.0;     // measured: distance to the reference / |d|
  Eigen::MatrixXd V;
};

double relative_error(const Eigen::MatrixXd& V, const Eigen::MatrixXd& reference, const Eigen::Vector3d& d) {
  if (reference.size() == 0) return NAN;  // --no-reference
  return (V - reference).rowwise().norm().maxCoeff() / d.norm();
}

OurRun run_ours(const pb::HeightFieldProblem& problem, const pd::RegionOfInterest& roi,
                pd::DeformOptions options, const Eigen::MatrixXd& reference) {
  auto mesh = std::make_shared<const pd::Mesh>(problem.mesh);
  const auto start = std::chrono::steady_clock::now();
  pd::Deformer deformer(mesh, roi, options);
  OurRun run;
  run.precompute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const pd::DeformResult r = deformer.solve(problem.d);
  run.factorize_ms = r.timing.factorize;
  run.converge_ms = r.timing.factorize + r.timing.solve;
  run.iterations = r.iterations;
  run.probe_evaluations = r.probe_evaluations;
  run.converged = r.converged;
  run.smooth_start = r.smooth_start;
  run.coarse_start = r.coarse_start;
  run.coarse_evaluations = r.coarse_evaluations;
  run.estimate = r.error_estimate.value_or(NAN);
  run.error = relative_error(r.V, reference, problem.d);
  run.V = r.V;
  // Per-iteration cost with the factorization in place: a fixed number of iterations, no early stop.
  options.max_iterations = kTimedIterations;
  options.tolerance = 0.0;
  options.energy_tolerance = 0.0;
  pd::Deformer timed(mesh, roi, options);
  (void)timed.solve(problem.d);  // factorizes; the timed ones reuse the factorization
  std::vector<double> per_iteration;
  for (int k = 0; k < kTimedSolves; ++k) per_iteration.push_back(timed.solve(problem.d).timing.per_iteration);
  std::nth_element(per_iteration.begin(), per_iteration.begin() + kTimedSolves / 2, per_iteration.end());
  run.per_iteration_ms = per_iteration[kTimedSolves / 2];
  return run;
}

void print_row(long vertices, const char* method, const char* setting, const OurRun& r) {
  std::printf("%8ld %-8s %-15s %9.1f %9.1f %8.2f %5d+%-3d%s %10.1f %8.1e %8.1e\n", vertices, method, setting,
              r.precompute_ms, r.factorize_ms, r.per_iteration_ms, r.iterations, r.probe_evaluations,
              r.converged ? " " : "*", r.converge_ms, r.estimate, r.error);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, peer_rows = true, with_reference = true;
  std::vector<int> chosen_sides;
  std::vector<pd::Method> methods = {pd::Method::ArapSR, pd::Method::Asan};
  int coarse_start_min_free = pd::DeformOptions{}.coarse_start_min_free;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--quick") == 0) {
      quick = true;
    } else if (std::strcmp(argv[a], "--no-peer") == 0) {
      peer_rows = false;
    } else if (std::strcmp(argv[a], "--no-reference") == 0) {
      with_reference = false;
      peer_rows = false;  // CGAL runs to our measured accuracy
    } else if (std::strcmp(argv[a], "--side") == 0 && a + 1 < argc && std::atoi(argv[a + 1]) >= 3) {
      chosen_sides.push_back(std::atoi(argv[++a]));
    } else if (std::strcmp(argv[a], "--method") == 0 && a + 1 < argc &&
               (std::strcmp(argv[a + 1], "asan") == 0 || std::strcmp(argv[a + 1], "arap-sr") == 0)) {
      methods = {std::strcmp(argv[++a], "asan") == 0 ? pd::Method::Asan : pd::Method::ArapSR};
    } else if (std::strcmp(argv[a], "--coarse-start-min-free") == 0 && a + 1 < argc &&
               std::atoi(argv[a + 1]) >= -1) {
      coarse_start_min_free = std::atoi(argv[++a]);
    } else {
      std::fprintf(stderr,
                   "usage: deform_bench [--quick] [--no-peer] [--no-reference] [--side N]... "
                   "[--method arap-sr|asan] [--coarse-start-min-free N]\n");
      return 2;
    }
  }
#ifndef PUSHPULL_BENCH_WITH_CGAL
  (void)peer_rows;
#endif
  std::vector<int> sides = {100};
  if (!chosen_sides.empty()) {
    sides = chosen_sides;
  } else if (!quick) {
    sides.push_back(173);
    sides.push_back(316);
  }
  std::printf(
      "deform_bench: jittered height field, disk handle pulled by |d| = 0.1 along z, outer ring fixed\n");
  std::printf(
      "ours: default accuracy (estimated distance to the minimiser <= 1e-2 |d|); err/|d| measured against\n"
      "the same energy solved to 1e-9; times in ms; * = stopped by the iteration cap\n\n");
  std::printf("%8s %-8s %-15s %9s %9s %8s %-10s %10s %8s %8s\n", "vertices", "method", "setting", "precomp",
              "factorize", "per-iter", "iter+probe", "to-result", "estimate", "err/|d|");
  double per_iteration_10k = 0.0, per_iteration_100k = 0.0, asan_10k = 0.0, arap_sr_10k = 0.0,
         largest_ms = 0.0;
  for (const int n : sides) {
    const pb::HeightFieldProblem problem = pb::make_height_field(n);
    const long vertices = static_cast<long>(problem.mesh.V.rows());
    const pd::RegionOfInterest roi = pd::build_roi(problem.mesh, problem.handle, problem.fixed);
    std::printf("%8ld region: %zu free, %zu handle, %zu fixed vertices\n", vertices, roi.free.size(),
                roi.handle.size(), roi.fixed.size());
    for (const pd::Method method : methods) {
      const std::string name(pd::method_name(method));
      const Eigen::MatrixXd reference =
          with_reference ? pb::reference_solution(problem.mesh, roi, problem.d, method) : Eigen::MatrixXd();
      pd::DeformOptions options;
      options.method = method;
      options.coarse_start_min_free = coarse_start_min_free;
      options.threads = 1;
      const OurRun one = run_ours(problem, roi, options, reference);
      print_row(vertices, name.c_str(),
                one.coarse_start   ? "1 thr, coarse"
                : one.smooth_start ? "1 thr, smooth"
                                   : "1 thread",
                one);
      options.threads = 0;
      const OurRun two = run_ours(problem, roi, options, reference);
      print_row(vertices, name.c_str(),
                two.coarse_start   ? "2 thr, coarse"
                : two.smooth_start ? "2 thr, smooth"
                                   : "2 threads",
                two);
      if (two.coarse_start) {  // the same solve without the coarse level, in this run
        pd::DeformOptions without = options;
        without.coarse_start_min_free = -1;
        const OurRun fine_only = run_ours(problem, roi, without, reference);
        print_row(vertices, name.c_str(), fine_only.smooth_start ? "2 thr, smooth" : "2 thr, rest",
                  fine_only);
        std::printf("%8s (coarse: its coarse solve took %d local-global steps on %s)\n", "",
                    two.coarse_evaluations, "about a ninth of the free vertices");
      }
      if (two.smooth_start) {  // the same solve from the rest start, for comparison in this run
        pd::DeformOptions rest = options;
        rest.smooth_start_min_free = -1;
        print_row(vertices, name.c_str(), "2 thr, rest", run_ours(problem, roi, rest, reference));
      }
      const OurRun paper = run_ours(problem, roi, pd::paper_iterations(options), reference);
      print_row(vertices, name.c_str(), "paper: 50 plain", paper);
      largest_ms = std::max(largest_ms, two.precompute_ms + two.converge_ms);
      if (n == 100) {
        per_iteration_10k = std::max(per_iteration_10k, two.per_iteration_ms);
        (method == pd::Method::Asan ? asan_10k : arap_sr_10k) = two.converge_ms;
      }
      if (n == 316) per_iteration_100k = std::max(per_iteration_100k, two.per_iteration_ms);
#ifdef PUSHPULL_BENCH_WITH_CGAL
      if (method == pd::Method::ArapSR && peer_rows) {
        // Like for like: the arap-sr energy, one thread each, CGAL run to our 1-thread result's accuracy.
        const pb::PeerRun peer =
            pb::run_cgal_spokes_and_rims(problem.mesh, problem.handle, problem.fixed, problem.d, reference,
                                         one.error * problem.d.norm(), 2000);
        std::printf(
            "%8ld %-8s %-15s %9.1f %9s %8.2f %5d    %s %10.1f %8s %8.1e   ratio %.1fx (CGAL / ours, 1 thread "
            "each, same accuracy)\n",
            vertices, name.c_str(), "CGAL, 1 thread", peer.preprocess_ms, "-", peer.per_iteration_ms,
            peer.iterations, peer.converged ? " " : "*", peer.converge_ms, "-", peer.error / problem.d.norm(),
            peer.converge_ms / (one.precompute_ms + one.converge_ms));
      }
#endif
      std::fflush(stdout);
    }
  }
  std::printf(
      "\nto-result = factorize + iterations (ours; precompute = symbolic analysis and clusters, once per "
      "region);\n"
      "CGAL: preprocess (its matrix and factorization) + iterations, run until within our 1-thread arap-sr "
      "error\n"
      "of the reference; ratio = CGAL to-result / (our precompute + to-result);\n"
      "iter+probe: iterations and the rate probe's local-global steps (per-iter is the cost of either);\n"
      "smooth / rest: a cold solve from the constrained moves spread biharmonically (the default from %d "
      "free\n"
      "vertices on; factorize includes its factorization) / from the rest positions;\n"
      "coarse: a cold solve started coarse-to-fine (from %d free vertices on; factorize "
      "includes\n"
      "building the coarser region, the solve its coarse solve; iters are the fine ones).\n",
      pd::DeformOptions{}.smooth_start_min_free, coarse_start_min_free);
  // The targets read the 10K and 100K rows of both methods: a run with --side and neither size, or with
  // --method, prints none.
  const bool both_methods = methods.size() == 2;
  const bool has_10k = both_methods && std::find(sides.begin(), sides.end(), 100) != sides.end();
  const bool has_100k = both_methods && std::find(sides.begin(), sides.end(), 316) != sides.end();
  if (has_10k || has_100k) std::printf("targets (issue 9):");
  if (has_10k) {
    std::printf(
        " asan at 10K %.1f ms (<= 60: %s); arap-sr at 10K %.1f ms (<= 40: %s); per iteration\n"
        "%.2f ms at 10K (<= 1.5: %s)",
        asan_10k, asan_10k <= 60.0 ? "met" : "NOT met", arap_sr_10k, arap_sr_10k <= 40.0 ? "met" : "NOT met",
        per_iteration_10k, per_iteration_10k <= 1.5 ? "met" : "NOT met");
  }
  if (has_100k) {
    std::printf("%s%.2f ms per iteration at 100K (<= 25: %s)", has_10k ? ", " : " ", per_iteration_100k,
                per_iteration_100k <= 25.0 ? "met" : "NOT met");
    if (has_10k) {
      std::printf(", growth %.1fx (<= 15: %s)", per_iteration_100k / per_iteration_10k,
                  per_iteration_100k / per_iteration_10k <= 15.0 ? "met" : "NOT met");
    }
    std::printf("; slowest 100K result %.0f ms (<= 1000: %s)", largest_ms,
                largest_ms <= 1000.0 ? "met" : "NOT met");
  }
  if (has_10k || has_100k) std::printf("\n");
  return 0;
}
