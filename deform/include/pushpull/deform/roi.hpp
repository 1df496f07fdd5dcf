// pushpull::deform::RegionOfInterest: which vertices a push/pull may move.
//
// Every vertex of the mesh has one role:
//   Outside: not part of the region Omega; never moves.
//   Free:    an unknown of the deformation.
//   Handle:  moved to a prescribed target (by the push/pull displacement d).
//   Fixed:   held at a prescribed position (its rest position for a plain push/pull). Fixed vertices are the
//            user's fixed set F as far as it bounds Omega, plus the boundary of Omega (Omega vertices that
//            share an edge with an Outside vertex).
// The energy is defined on the triangles whose three vertices are all in Omega.
//
// Index lists are sorted ascending and hold mesh vertex indices (rows of Mesh::V).
// Ownership: a plain value type. Thread-safety: none of its own.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform {

enum class VertexRole : std::uint8_t { Outside, Free, Handle, Fixed };

struct RegionOfInterest {
  std::vector<VertexRole> role;  // #V, the role of every mesh vertex
  std::vector<int> handle;       // vertices with role Handle, sorted
  std::vector<int> fixed;        // vertices with role Fixed, sorted
  std::vector<int> free;         // vertices with role Free, sorted
  // Human-readable notes about the region: handles close to the fixed boundary (the paper's conclusion asks
  // to tell the user, the result may then differ from what they expect), vertices listed twice, ...
  std::vector<std::string> warnings;
  // Whether Omega is made of whole connected parts: no vertex of it shares an edge with an Outside vertex.
  // With no Fixed vertex, such a region moves with its handle as one piece; a region with no Fixed vertex
  // that is not whole (Omega is the handle alone, e.g. build_roi with max_distance 0) leaves its handle torn
  // from the surface around it.
  bool whole_parts = false;

  [[nodiscard]] std::size_t size() const { return handle.size() + fixed.size() + free.size(); }
  [[nodiscard]] bool contains(int vertex) const {
    return role.at(static_cast<std::size_t>(vertex)) != VertexRole::Outside;
  }
};

struct RoiOptions {
  // A warning is added for each handle vertex at most this many edges (rings) away from a Fixed vertex.
  int near_boundary_rings = 3;
};

// Region growing as in the paper (section 6): breadth-first over mesh edges, starting at `handle`, never
// expanding past a vertex of `fixed` (it joins Omega as Fixed) nor past `max_distance`.
// Distance: geodesic along edges, i.e. the shortest path length (sum of Euclidean edge lengths, model
// units) from the nearest handle vertex (multi-source Dijkstra). Vertices farther than max_distance stay
// Outside; Omega vertices next to them become Fixed. max_distance = infinity: the whole connected
// component(s) of the handle up to F. Throws std::invalid_argument when: handle is empty, an index is out of
// range, a vertex is both handle and fixed, max_distance is NaN or negative.
[[nodiscard]] RegionOfInterest build_roi(const Mesh& mesh, std::span<const int> handle,
                                         std::span<const int> fixed,
                                         double max_distance = std::numeric_limits<double>::infinity(),
                                         const RoiOptions& options = {});

// Explicit region: Omega = region u handle u fixed. Vertices of Omega next to an Outside vertex become Fixed
// (handles stay Handle). Same preconditions as build_roi. An empty `region` means "every vertex" (whole
// mesh).
[[nodiscard]] RegionOfInterest make_roi(const Mesh& mesh, std::span<const int> handle,
                                        std::span<const int> fixed, std::span<const int> region,
                                        const RoiOptions& options = {});

// From a per-vertex selection as in the ARAP benchmark .sel files: 0 = fixed, 1 = free (ROI), 2 = handle,
// anything else (e.g. -1) = outside. Throws if selection.size() != #V or no vertex is a handle.
[[nodiscard]] RegionOfInterest roi_from_selection(const Mesh& mesh, std::span<const int> selection,
                                                  const RoiOptions& options = {});

}  // namespace pushpull::deform
