// Private: the state behind Deformer (see deformer.hpp): local numbering, energy model, factorization.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anderson.hpp"
#include "coarse_start.hpp"
#include "energy_model.hpp"
#include "global_system.hpp"
#include "helper_thread.hpp"
#include "pushpull/deform/deformer.hpp"
#include "smooth_start.hpp"

namespace pushpull::deform {
namespace detail {
struct VertexGraph;
}

struct Deformer::Impl {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  DeformOptions options;
  ValidationReport validation;
  std::vector<std::string> setup_warnings;  // validation + region + pinned components
  double precompute_ms = 0.0;

  // Local numbering of Omega: [0, n_free) free, then handle, fixed, pinned (constrained, in that order).
  std::vector<int> local_to_global;
  int n_free = 0, n_handle = 0, n_fixed = 0, n_pinned = 0;
  // Rest positions relative to `origin`, the region's centroid on a coarse grid (model units; deformer.cpp),
  // as are the solver's iterates:
  // with the model's own coordinates a region far from the model's origin lost digits in tr(X Q X^T) (the
  // energy the Anderson safeguard compares) and in asan's stretched copy; the bonnet (examples/hood.off)
  // moved 3 m from its origin took 158 asan iterations instead of 117, (100, 200, 1) km off 663.
  Eigen::Matrix3Xd P;  // 3 by n
  // Parts of the region that no fixed vertex holds (a separate part pressed whole: a lamp, a trim; free
  // vertices enclosed by handle vertices), connected through free vertices only: group g's free vertices
  // (local indices) are unheld_free[unheld_free_start[g], unheld_free_start[g + 1]), the handle vertices next
  // to them (columns of the constrained block, 0 = the first handle vertex) unheld_handle[...] likewise. Each
  // solve with a tolerance starts them moved by the mean move of those handle vertices: a rigid translation,
  // the exact minimiser of every method's energy when the handle moves by one d and the group touches nothing
  // else.
  std::vector<int> unheld_free, unheld_free_start{0}, unheld_handle, unheld_handle_start{0};
  // Whether the translation is the minimiser needs more: when every free vertex is unheld and none of the
  // connected parts of the region they lie in (through every vertex of Omega) has a fixed vertex,
  // free_in_whole_parts is set and part p's handle vertices (columns as above) are
  // whole_part_handle[whole_part_start[p], whole_part_start[p + 1]); those parts can move rigidly.
  bool free_in_whole_parts = false;
  std::vector<int> whole_part_handle, whole_part_start{0};
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  // The constrained vertices' positions of the current solve in model coordinates (3 by n - n_free: handle
  // targets, fixed targets or rest, pinned at rest), written back as given so that they round-trip exactly.
  Eigen::Matrix3Xd constrained_model;
  Eigen::MatrixX3i faces;  // Omega's triangles in local indices
  Eigen::VectorXd rest_half_cot;
  double mollify_eps = 0.0;  // triangle-inequality margin of the mollified weights (cotangent.hpp)

  detail::EnergyModel model;
  detail::GlobalSystem system;
  bool factored = false;
  long factorizations = 0;  // numeric factorizations done so far (weights recomputed or first solve)
  std::optional<Eigen::Vector3d> weight_direction;  // unit d_o of the current ASAN weights
  // asan cold solves' biharmonic start (DeformOptions::smooth_start_min_free), prepared at the first one
  // (its factorization is independent of the weights and of d); smooth_start_failed: L_ff could not be
  // factored, cold solves start from rest.
  detail::SmoothStart smooth_start;
  bool smooth_start_failed = false;
  // asan cold solves' coarse-to-fine start (DeformOptions::coarse_start_min_free), prepared at the first
  // one; coarse_start_failed: the region did not coarsen (or the coarse Deformer could not be built).
  detail::CoarseStart coarse_start;
  bool coarse_start_failed = false;

  // The local step runs in two fixed parts, clusters [0, split_cluster) and [split_cluster, #clusters),
  // whatever the thread count, so results do not depend on it. Right-hand-side contributions of part 1
  // to free vertices also reached by part 0 (shared_vertex; shared_slot[v] its index, else -1) are kept
  // apart and added after both parts.
  int split_cluster = 0;
  std::vector<int> shared_slot, shared_vertex;
  std::unique_ptr<detail::HelperThread> helper;  // runs part 1 during run() on large regions (else null)

  void setup();
  // unheld_* from Omega's vertex graph (global indices) once the local numbering is made.
  void group_unheld_vertices(const detail::VertexGraph& graph, const std::vector<int>& global_to_local);
  // Starts each unheld group of X (3 by n, constrained columns already set) at its handle's mean move.
  // When that is the minimiser, returns the largest distance of a handle vertex's move from its part's mean
  // move (model units): free_in_whole_parts and each part's handle vertices moved alike (to 1e-9 of the move,
  // e.g. rest + d rounded at a model's coordinates 1 km off), so the part moves rigidly, and an energy that a
  // rigid motion brings to its minimum, zero (every method but arap-s, whose negative weights can take it
  // lower). Else empty.
  [[nodiscard]] std::optional<double> start_unheld_groups(Eigen::Matrix3Xd& X) const;
  void plan_local_split();  // split_cluster, shared_slot, shared_vertex from the model's clusters
  // Recomputes weights if d_o changed (ASAN) and refactors when needed; returns milliseconds spent.
  double prepare_weights(const Eigen::Vector3d& push_direction, std::vector<std::string>& warnings);
  // Optimal rotations for X (3 by n) into R, warm-started by q; returns the energy E(X, R). sr-arap couples
  // neighbouring rotations: Gauss-Seidel sweeps starting from R, or from the uncoupled optimum when `R_valid`
  // is false, at most `sweeps` of them, fewer once a sweep changes no entry of any rotation by more than
  // `sweep_tolerance` (0: always `sweeps`).
  // `quadratic`, when given, is tr(X Q X^T) already known (after a plain global step), saving a pass over Q.
  // `rhs`, when given, receives B_f(R) (3 by n_free, b_v = sum_t R_cluster(t) g_t over free v) for the
  // returned R, accumulated while each cluster's terms are in cache. `threads`, when given, runs the two
  // parts of the step concurrently (same results as without).
  double local_step(const Eigen::Matrix3Xd& X, std::vector<Eigen::Matrix3d>& R,
                    std::vector<Eigen::Quaterniond>& q, bool R_valid = true, int sweeps = 1,
                    std::optional<double> quadratic = std::nullopt, Eigen::Matrix3Xd* rhs = nullptr,
                    detail::HelperThread* threads = nullptr, double sweep_tolerance = 0.0) const;
  // Free positions X_f minimising E(., R) given constrained positions (through rhs_c = -Q_fc X_c), with
  // B_f = B_f(R) from local_step. Writes X_f into G (3 by n_free). Also returns tr(X Q X^T) of the result,
  // = X_f : (B_f - rhs_c) + constrained_quadratic since Q_ff X_f = B_f + rhs_c.
  // `threads`, when given, splits the triangular solves over two threads (same results as without).
  void global_step(const Eigen::Matrix3Xd& B, const Eigen::Matrix3Xd& rhs_c, double constrained_quadratic,
                   Eigen::Matrix3Xd& G, double& quadratic, detail::HelperThread* threads = nullptr) const;
  // Whole-mesh positions (model coordinates): the free columns of X (relative to origin) and
  // constrained_model.
  [[nodiscard]] Eigen::MatrixXd to_full(const Eigen::Matrix3Xd& X) const;
  // rate_hint, rate_hint_settled: ConstraintTargets' (with a warm start).
  DeformResult run(const Eigen::Matrix3Xd& X_c, const Eigen::Vector3d& push_direction,
                   const Eigen::MatrixXd& initial_guess, std::optional<double> rate_hint,
                   bool rate_hint_settled, const ProgressCallback& progress);
};

}  // namespace pushpull::deform
