#include "coarse_start.hpp"

#include <algorithm>
#include <exception>

#include "region_coarsening.hpp"
#include "rotation.hpp"

namespace pushpull::deform::detail {
namespace {

// The coarse region keeps about this fraction of the free vertices: with a ninth, the 10K height field's
// coarse solve cost about a third of the fine iterations it saved; a quarter saved hardly more fine
// iterations at three times the coarse cost (a scratch driver on 2026-12-05, not in the tree).
constexpr int kCoarsening = 9;

}  // namespace

CoarseStart::CoarseStart() = default;
CoarseStart::~CoarseStart() = default;
CoarseStart::CoarseStart(CoarseStart&&) noexcept = default;
CoarseStart& CoarseStart::operator=(CoarseStart&&) noexcept = default;

bool CoarseStart::prepare(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& origin,
                          const Eigen::MatrixX3i& faces, int n_free, int n_handle,
                          const DeformOptions& options) {
  coarse_.reset();
  const CoarseRegion region = coarsen_region(P, faces, n_free, n_free / kCoarsening);
  if (3 * (n_free - region.kept_free) < n_free) return false;
  const int m = static_cast<int>(region.kept.size());
  auto mesh = std::make_shared<Mesh>();
  mesh->V.resize(m, 3);
  for (int k = 0; k < m; ++k)
    mesh->V.row(k) = (P.col(region.kept[static_cast<std::size_t>(k)]) + origin).transpose();
  mesh->F = region.faces;
  std::vector<int> handle, fixed, all(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    all[static_cast<std::size_t>(k)] = k;
    const int local = region.kept[static_cast<std::size_t>(k)];
    if (local >= n_free + n_handle)
      fixed.push_back(k);
    else if (local >= n_free)
      handle.push_back(k);
  }
  DeformOptions coarse_options = options;
  coarse_options.progress = {};
  coarse_options.validate = false;
  try {
    RegionOfInterest roi = make_roi(*mesh, handle, fixed, all);
    coarse_ = std::make_unique<Deformer>(std::move(mesh), std::move(roi), coarse_options);
  } catch (const std::exception&) {
    coarse_.reset();
    return false;
  }
  origin_ = origin;
  n_free_ = n_free;
  kept_ = region.kept;
  ancestor_ = region.ancestor;
  coarse_ring_.assign(static_cast<std::size_t>(m), {});
  for (Eigen::Index f = 0; f < region.faces.rows(); ++f) {
    for (int e = 0; e < 3; ++e) {
      const int a = region.faces(f, e), b = region.faces(f, (e + 1) % 3);
      coarse_ring_[static_cast<std::size_t>(a)].push_back(b);
      coarse_ring_[static_cast<std::size_t>(b)].push_back(a);
    }
  }
  for (std::vector<int>& ring : coarse_ring_) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  return true;
}

std::optional<CoarseStart::Start> CoarseStart::start(const Eigen::Matrix3Xd& P, const Eigen::Matrix3Xd& X_c,
                                                     const Eigen::Vector3d& push_direction,
                                                     const std::function<bool()>& go_on) {
  if (!coarse_) return std::nullopt;
  const RegionOfInterest& roi = coarse_->roi();
  ConstraintTargets targets;
  targets.handle_positions.resize(static_cast<Eigen::Index>(roi.handle.size()), 3);
  targets.fixed_positions.resize(static_cast<Eigen::Index>(roi.fixed.size()), 3);
  for (std::size_t k = 0; k < roi.handle.size(); ++k)
    targets.handle_positions.row(static_cast<Eigen::Index>(k)) =
        (X_c.col(kept_[static_cast<std::size_t>(roi.handle[k])] - n_free_) + origin_).transpose();
  for (std::size_t k = 0; k < roi.fixed.size(); ++k)
    targets.fixed_positions.row(static_cast<Eigen::Index>(k)) =
        (X_c.col(kept_[static_cast<std::size_t>(roi.fixed[k])] - n_free_) + origin_).transpose();
  targets.push_direction = push_direction;
  // A cold solve with its own rate probe (and a coarser level of its own when still large): hinted instead
  // (an unsettled hint of rate 0: no probe, no level of its own) the 10K height field's coarse solve stopped
  // after 8 evaluations, far from its minimiser, and the fine solve took 72 iterations instead of 40.
  // The caller's callback may throw: its exception goes on to the caller, not into the catch below (which
  // stands for the coarse solve's own failures).
  std::exception_ptr thrown;
  ProgressCallback progress;
  if (go_on) {
    progress = [&go_on, &thrown](const IterationReport&) {
      try {
        return go_on();
      } catch (...) {
        thrown = std::current_exception();
        return false;
      }
    };
  }
  DeformResult solved;
  try {
    solved = coarse_->solve(targets, progress);
  } catch (const std::exception&) {
    if (thrown) std::rethrow_exception(thrown);
    return std::nullopt;
  }
  if (thrown) std::rethrow_exception(thrown);
  const int evaluations = solved.iterations + solved.probe_evaluations + solved.coarse_evaluations;
  if (solved.cancelled) {
    Start cancelled;
    cancelled.cancelled = true;
    cancelled.evaluations = evaluations;
    return cancelled;
  }
  // Not converged (at the iteration cap) is still a start; only non-finite positions are none.
  if (!solved.V.allFinite()) return std::nullopt;

  const int m = static_cast<int>(kept_.size());
  Eigen::Matrix3Xd X(3, m);  // coarse solved positions, local
  for (int k = 0; k < m; ++k) X.col(k) = solved.V.row(k).transpose() - origin_;
  // The rotation that best maps each coarse vertex's one-ring from rest to solved.
  std::vector<Eigen::Matrix3d> R(static_cast<std::size_t>(m), Eigen::Matrix3d::Identity());
  for (int k = 0; k < m; ++k) {
    const int rest_k = kept_[static_cast<std::size_t>(k)];
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (int w : coarse_ring_[static_cast<std::size_t>(k)])
      S += (X.col(w) - X.col(k)) * (P.col(kept_[static_cast<std::size_t>(w)]) - P.col(rest_k)).transpose();
    // A ring on one line (rank 1) leaves the twist about it undetermined: identity then.
    if (!S.allFinite() || !(S.squaredNorm() > 0.0)) continue;
    if (const std::optional<Eigen::Matrix3d> fitted = closest_rotation_of_rank_two(S, 1e-9))
      R[static_cast<std::size_t>(k)] = *fitted;
  }
  Start start;
  start.free.resize(3, n_free_);
  for (int u = 0; u < n_free_; ++u) {
    const int a = ancestor_[static_cast<std::size_t>(u)];
    const int rest_a = kept_[static_cast<std::size_t>(a)];
    start.free.col(u) = X.col(a) + R[static_cast<std::size_t>(a)] * (P.col(u) - P.col(rest_a));
  }
  if (!start.free.allFinite()) return std::nullopt;
  start.rate = solved.contraction_rate;
  start.evaluations = evaluations;
  return start;
}

}  // namespace pushpull::deform::detail
