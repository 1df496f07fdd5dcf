// Private: the coarse-to-fine start of an asan cold solve on a large region (DeformOptions::
// coarse_start_min_free says when and what it gains).
//
// The slowly contracting modes of asan's local-global iterations are smooth (the region bending as a whole,
// soft along d), and they are what a cold solve of a large region spends most of its iterations on: the 10K
// height field took 85 iterations from rest, the 100K one 229. A coarser tessellation of the same region
// (region_coarsening.hpp: about a ninth of its free vertices, every constrained vertex kept) has the same
// smooth modes at a ninth of the cost per iteration. CoarseStart solves the same push/pull there (a Deformer
// of its own with the same options, so a coarse region still over the threshold coarsens again), then carries
// the coarse shape to the fine region: each coarse vertex keeps its solved position, and each collapsed
// vertex follows the coarse vertex it was collapsed into rigidly, x_u = x_a + R_a (p_u - p_a), with R_a the
// rotation that best maps a's coarse one-ring from rest to solved (uniform weights). The fine iterations then
// start near the minimiser with the smooth modes already in place.
//
// The coarse solve also hands on its contraction rate, a floor under the fine estimate (the finer region's
// slowest mode contracts more slowly, local_global.cpp), but not in place of the fine solve's own rate probe:
// a fine solve started this close stops early, within the probe's window, and pays the probe's 40
// evaluations; that is why it pays only on the largest regions (deformer.hpp: coarse_start_min_free).
//
// Units and frames: local positions relative to the Deformer's origin (deformer_impl.hpp); `origin` puts them
// back in model coordinates for the coarse Deformer. Ownership: owns the coarse Deformer. Thread-safety: none
// (used by one solve at a time, like the Deformer that owns it).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "pushpull/deform/deformer.hpp"

namespace pushpull::deform::detail {

class CoarseStart {
 public:
  CoarseStart();
  ~CoarseStart();
  CoarseStart(CoarseStart&&) noexcept;
  CoarseStart& operator=(CoarseStart&&) noexcept;

  // P: 3 by n local rest positions ([0, n_free) free, then n_handle handle vertices, then the other
  // constrained ones: fixed and pinned); faces: the region's triangles (local indices). Coarsens to about
  // n_free / 9 free vertices and builds the coarse Deformer with `options` (no progress callback, no
  // validation: the region was validated). Returns false, leaving it unprepared, when coarsening removes too
  // little (under a third of the free vertices: a tessellation of small patches with few interior vertices)
  // or the coarse Deformer cannot be built; the solve then starts as it would without.
  bool prepare(const Eigen::Matrix3Xd& P, const Eigen::Vector3d& origin, const Eigen::MatrixX3i& faces,
               int n_free, int n_handle, const DeformOptions& options);
  [[nodiscard]] bool prepared() const { return coarse_ != nullptr; }

  struct Start {
    Eigen::Matrix3Xd free;       // 3 by n_free: the fine free vertices' starting positions (local)
    std::optional<double> rate;  // the coarse solve's contraction rate (empty: none known)
    int evaluations = 0;         // local-global evaluations of the coarse solve
    bool cancelled = false;      // go_on returned false: the solve is abandoned (free empty)
  };
  // P: the rest positions given to prepare(); X_c: 3 by n - n_free, the constrained vertices' targets
  // (local). go_on, when set, is asked after every
  // coarse iteration (and rate probe step) whether to go on; an exception from it propagates. A coarse solve
  // stopped at its iteration cap still gives a start. Empty when the coarse solve fails (throws, or gives
  // non-finite positions): the caller starts as without, and should not try again.
  [[nodiscard]] std::optional<Start> start(const Eigen::Matrix3Xd& P, const Eigen::Matrix3Xd& X_c,
                                           const Eigen::Vector3d& push_direction,
                                           const std::function<bool()>& go_on = {});

 private:
  std::unique_ptr<Deformer> coarse_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  int n_free_ = 0;
  std::vector<int> kept_;                      // coarse vertex k = fine local vertex kept_[k]
  std::vector<int> ancestor_;                  // fine local vertex -> coarse vertex
  std::vector<std::vector<int>> coarse_ring_;  // coarse vertex -> its coarse neighbours
};

}  // namespace pushpull::deform::detail
