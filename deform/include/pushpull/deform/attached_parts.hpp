// pushpull::deform::AttachedParts: lamps, lenses, number plates, grilles and trims that ride on the solved
// surface follow it.
//
// A car is many welded components; the region of interest grows along the surface from the handle, so it
// covers (part of) one body component and never the parts lying on it. Left alone they stay put while the
// body moves: a plate is swallowed by a pulled nose, a lamp cuts through its moved panel. Each such part is
// therefore bound to the solved surface at rest and carried along:
//
// - Which parts: every component with no vertex in the region that has a vertex within `reach` of a region
//   triangle at rest. A component is either solved (it holds region vertices) or moves whole: no part is
//   ever split between moving and staying. A part that does not lie on the surface (below) and is larger than
//   the region (bounding-box diagonals at rest) is left out: a reviewer who grabs a windscreen or a lamp (the
//   region is then that whole component, with no border to hold it) moves that part, and the car's body under
//   it, within reach but no part of it, used to follow it as one rigid piece (the ToyCar's windscreen lifted
//   the whole body by the pull).
// - How, for a part lying on the surface (at least 90% of its vertices within reach of the solved surface:
//   a lamp lens, a plate, a trim, a window): each vertex binds to its closest point on the carrier surface
//   (all triangles of the solved components, moving or not) as that triangle, its barycentric coordinates
//   and its offset from that point, as Blender's Surface Deform modifier binds a mesh to a target. After the
//   solve the bound point moves with the triangle and the offset turns with the surface around it: the
//   rotations of the triangle's corners blended by the barycentric coordinates (so the turn is continuous
//   from triangle to triangle, and the offset keeps its length), each corner's the best rotation (Kabsch) of
//   the patch made of it and rings of its neighbours, grown until the patch spreads as far across the surface
//   as the offsets it carries reach above it, which stays well defined on the sliver triangles of tessellated
//   CAD where a triangle's own normal flips on a tiny move. So the part keeps its height above the panel
//   under it everywhere (it never sinks in, which one rigid motion per part cannot promise on a panel that
//   bends under a long trim) and bends only as much as the panel does; a part straddling the region's border
//   stays attached to both sides without a tear. This was chosen over one rigid motion per part for those
//   reasons.
// - How, for a part that only comes close to the surface (a wheel in its arch, a seat behind a panel): the
//   same binding tells where its vertices would go; the part moves by the rigid motion that fits that best
//   when the fit is good (residual within 25% of the motion: the surface under it moves as one) and
//   otherwise stays where it is (a pulled wheel arch does not drag or bend the wheel inside it).
// - Vertices of a part whose carrier triangles did not move (nor any neighbour of their corners) keep their
//   exact values, even where the patches grown for the rotations reach into the moved region.
//
// Units: model units (reach too). Frame: model space. Shapes: positions #V by 3.
// Ownership: a value type holding the binding. Thread-safety: const members may run concurrently.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/roi.hpp"

namespace pushpull::deform {
namespace detail {
struct VertexGraph;
}

struct AttachOptions {
  // A part within this distance of a region triangle at rest follows the surface. <= 0: automatic,
  // 3% of the region's bounding-box diagonal (3 cm for a 1 m region).
  double reach = 0.0;
};

struct AttachedPart {
  int component = -1;         // connected component (of the face graph, numbered by lowest vertex)
  std::vector<int> vertices;  // its vertices, sorted
  double rest_gap = 0.0;      // its smallest distance to a region triangle at rest
  bool on_surface = false;    // follows the surface vertex by vertex (else rigidly or not at all)
};

class AttachedParts {
 public:
  AttachedParts() = default;
  // Binds the parts of `rest` near the region `roi` (roles for every vertex of rest). Throws
  // std::invalid_argument when roi does not match the mesh.
  AttachedParts(const Mesh& rest, const RegionOfInterest& roi, const AttachOptions& options = {});

  [[nodiscard]] const std::vector<AttachedPart>& parts() const { return parts_; }
  [[nodiscard]] double reach() const { return reach_; }
  [[nodiscard]] std::size_t vertex_count() const { return bound_vertex_.size(); }

  // Moves the bound vertices of V (#V by 3: the solver's result, region solved, the rest at rest) with the
  // surface under them. Vertices whose carrier triangle did not move keep their exact values.
  void apply(Eigen::MatrixXd& V) const;

 private:
  // The patches of the carrier vertices slot_vertex[slot] (the corners of each bound vertex's carrier face,
  // carrier_slot_): the vertex and rings of its neighbours, grown ring by ring until the patch's in-plane
  // spread (in_plane_spread) reaches the largest offset the patch carries, so that the rotation's error,
  // about the solve's error over the patch's spread, turns an offset by no more than the solve's error (on
  // the needle fans of tessellated CAD a vertex's neighbours alone can lie nearly on a line, and a part 6 cm
  // above them moved 4 mm where the surface under it moved 0.4 mm off the minimiser).
  void build_patches(const detail::VertexGraph& graph, const std::vector<int>& slot_vertex);
  // The RMS spread of `count` points along their second principal direction (model units), from the sums of
  // their positions and of their outer products.
  [[nodiscard]] static double in_plane_spread(const Eigen::Vector3d& sum, const Eigen::Matrix3d& sum_outer,
                                              std::size_t count);

  static constexpr double kOnSurfaceShare = 0.9;   // share of vertices within reach for "on the surface"
  static constexpr double kCoherentMotion = 0.25;  // rigid fit residual / motion (RMS) accepted
  static constexpr int kMinPatchRings = 1;         // a patch: the vertex and at least its neighbours
  static constexpr int kMaxPatchRings = 16;        // ... grown by at most this many rings
  static constexpr int kMaxPatchVertices = 512;    // ... or until it holds this many vertices
  static constexpr int kPatchPoints = 32;          // of which it keeps at most this many (see build_patches)
  std::vector<int> bound_vertex_;                  // mesh vertex
  std::vector<int> bound_part_;                    // index into parts_
  std::vector<int> carrier_face_;                  // row of F it is bound to
  std::vector<std::array<int, 3>> carrier_slot_;   // its carrier face's corners' patches (patch_start_)
  std::vector<Eigen::Vector3d> bary_;              // barycentric coordinates of the bound point
  std::vector<Eigen::Vector3d> offset_;            // vertex - bound point at rest (model space)
  // Per carrier vertex used, its patch: the vertex and the rings of neighbours around it, grown until the
  // patch's in-plane spread reaches the largest offset it carries (see build_patches).
  std::vector<int> patch_start_, patch_index_;
  // Per carrier vertex used, the vertex and its neighbours: the surface moved there when one of these did.
  std::vector<int> ring_start_, ring_index_;
  Eigen::MatrixXi F_;                              // the mesh's faces
  Eigen::MatrixXd rest_V_;                         // rest corners, to tell moved triangles from unmoved ones
  std::vector<AttachedPart> parts_;
  double reach_ = 0.0;
};

}  // namespace pushpull::deform
