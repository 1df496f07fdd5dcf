// Private: a coarser tessellation of a region of interest, for the coarse-to-fine start (coarse_start.hpp).
//
// Half-edge collapses u -> v, in rounds that each collapse every free vertex not next to a collapse of the
// round into its nearest neighbour that allows it: the free vertex u is removed and its triangles are handed
// to its neighbour v, so the coarse vertices are a subset of the region's (no new positions) and every
// constrained vertex (handle, fixed, pinned) stays. A collapse is made only where it keeps the surface a
// surface: u is an interior manifold vertex (its triangles form one closed fan), the edge passes the link
// condition (u and v share exactly the two neighbours opposite the edge), and no triangle handed to v turns
// by more than 60 degrees or becomes much thinner than the ones it replaces. Patch borders, non-manifold
// edges and the region's own border therefore stay as they are; on a tessellated CAD body fewer vertices can
// go.
//
// Units and frames: those of the positions given (the Deformer's local rest positions). Thread-safety: a pure
// function.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pushpull::deform::detail {

struct CoarseRegion {
  // The kept vertices (indices into the given positions, ascending): every constrained vertex, and the free
  // ones not collapsed. Coarse vertex k is kept[k].
  std::vector<int> kept;
  int kept_free = 0;       // kept vertices below n_free (the free ones come first in `kept`)
  Eigen::MatrixX3i faces;  // the coarse triangles, in coarse indices
  // For every given vertex, the coarse vertex it was collapsed into (following the chain of collapses; a kept
  // vertex maps to itself).
  std::vector<int> ancestor;
};

// positions: 3 by n (vertices [0, n_free) free, the others constrained); faces: the region's triangles.
// Collapses free vertices until at most target_free remain or no allowed collapse is left. Degenerate
// triangles (repeated vertices) in `faces` are ignored.
[[nodiscard]] CoarseRegion coarsen_region(const Eigen::Matrix3Xd& positions, const Eigen::MatrixX3i& faces,
                                          int n_free, int target_free);

}  // namespace pushpull::deform::detail
