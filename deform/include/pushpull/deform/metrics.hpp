// pushpull::deform metrics: the evaluation of Le Vaou et al. 2020 (section 5) as numbers.
//
//  - Discrete Gaussian curvature per vertex: the angle defect divided by the mixed Voronoi area
//    (Meyer, Desbrun, Schroeder, Barr 2003: Voronoi area for non-obtuse triangles, half / quarter of the
//    triangle area for obtuse ones). Interior vertex: defect 2 pi - sum of incident angles. Boundary vertex
//    (on an edge used by one face): defect pi - sum of angles (the discrete geodesic-curvature turn);
//    it is reported but excluded from sign statistics, since it measures the boundary curve, not the surface.
//    So is a vertex on a non-manifold edge (three or more faces: sheets of tessellated CAD meeting), whose
//    angles do not close one disc.
//  - Its sign, one rule for every consumer (deform's metrics, `pushpull render`, the headset): a vertex is
//    flat (sign 0) when |K| L^2 <= flat_band, with L = curvature_reference_length(V), the diagonal of the
//    model's bounding box, and flat_band dimensionless (kDefaultFlatBand = 1e-2: flatter than a sphere of
//    radius 10 L, i.e. sqrt(R1 R2) >= 10 L for principal radii R1, R2). K L^2 is scale-free, so a 7 cm toy
//    car and a 4 m car read alike, and unlike a fraction of max |K| it does not depend on the sharpest tiny
//    part (a lamp's rim made every body vertex "flat"). Why 1e-2: a car bonnet is convex but gentle; the
//    demo's bonnet (examples/hood.off) has |K| L^2 between 1e-2 and 1 everywhere, and the paper's Fig. 12
//    finding (ARAP-s&r turns part of it saddle-shaped, ASAN keeps it convex) holds with 1e-2 (29% vs 0%
//    reversals on its alternating-diagonal grid; 22% vs 6.8% with uniform diagonals: the README) but vanishes
//    with 0.1 (half of ASAN's bonnet ends "flat") or 1 (the whole bonnet is flat before the pull). Float32
//    positions give planar panels an angle-defect noise estimated at 1e-3 .. 1e-2 in these units for 1-5 cm
//    triangles on a car, and the display rule below draws flat panels flat. Near-developable panels (doors)
//    are where the sign is least stable; a larger --dead-band (0.1 .. 1) draws them flat at the price above.
//    The paper's yellow/blue sign maps become +1 / -1 / 0 here.
//  - Flat panels shown flat: the angle defect at a vertex where only flat panels meet (creases meeting at a
//    corner of a coarse CAD panel) is not the curvature of those panels, yet interpolating vertex colours
//    paints the whole panel with it. flat_panel_faces() marks the faces whose every edge is a boundary, a
//    crease (dihedral angle >= crease angle) or shared with a coplanar face (dihedral <= kCoplanarDihedral);
//    displays draw those faces flat and a vertex with its vertex sign only where one of its faces is not a
//    flat-panel face (display_curvature_signs). Statistics keep the vertex signs.
//  - Sign changes are reported apart: strict reversals (+ to -, - to +) are the paper's "curvature sign
//    changes" (Fig. 4) that mark surface collapse (section 5); moves into or out of flat are counted
//    separately (into_flat, out_of_flat).
//  - Reversals by band: the same strict reversals counted again among the vertices clearly curved before
//    the pull, signed under the sign rule's band raised (MetricsOptions::reversal_bands, default 0.1, 1 and
//    10: curvature radius below L / sqrt(band), on a 4.4 m car 14 m, 4.4 m and 1.4 m; the "compared"
//    count), and signed the other way after it under the sign rule's own band (a clearly curved vertex
//    that turns gently curved the other way has reversed). They tell where a method's reversals lie: on
//    gently curved surface, on clearly curved
//    surface, or where the surface is nearly developable and the sign least stable (the paper's section 6
//    names areas of null Gaussian curvature as its criterion's weak spot). The README gives the bundled car's
//    session's figures.
//  - Displacement u_i = p'_i - p_i split along the unit push/pull direction d^ = d/|d|:
//    along_i = u_i . d^ (signed scalar) and orthogonal_i = u_i - along_i d^ (vector in the plane
//    perpendicular to d), as in the paper's Fig. 13.
//  - Norms over a vertex set S (the region of interest): rms = sqrt(sum_S x^2 / |S|), max = max_S |x|,
//    l2 = sqrt(sum_S x^2). The headline numbers in reports are the RMS ones.
//  - Section curves: the mesh cut by the plane through `origin + offset d^` with normal d^, chained into
//    polylines (closed loops or open chains), before and after the deformation.
//
// Units: lengths in model units, curvature in 1/length^2, areas in length^2, angles in radians.
// Shapes: V is #V by 3, F is #F by 3. Vertex sets are lists of mesh vertex indices.
// Thread-safety: free functions without state; safe to call concurrently on distinct outputs.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform {

struct GaussianCurvature {
  Eigen::VectorXd angle_defect;  // #V, radians (2 pi - sum angles inside, pi - sum angles on the boundary)
  Eigen::VectorXd area;          // #V, mixed Voronoi area
  Eigen::VectorXd K;             // #V, angle_defect / area (0 where the area is 0)
  std::vector<bool> boundary;    // #V, true on a boundary edge (an edge of exactly one face)
  // #V, true on an edge of three or more faces (sheets meeting, as in tessellated CAD): the angles around
  // such a vertex do not close one disc, so its angle defect (2 pi - their sum) is not a curvature.
  std::vector<bool> non_manifold;
  // Whether vertex i has a surface curvature: neither on the boundary nor on a non-manifold edge.
  [[nodiscard]] bool defined_at(std::size_t i) const { return !boundary[i] && !non_manifold[i]; }
};

// Angle defect and mixed area per vertex. Degenerate faces contribute nothing. Throws std::invalid_argument
// if F refers to a vertex outside V.
[[nodiscard]] GaussianCurvature gaussian_curvature(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Angle defects at most this large (radians) are rounding noise: a flat vertex, whatever its area.
inline constexpr double kFlatAngleDefect = 1e-10;

// The flat band of the sign rule: |K| L^2 at most this counts as flat (dimensionless; see the header).
inline constexpr double kDefaultFlatBand = 1e-2;

// L of the sign rule: the diagonal of the bounding box of V's rows (#V by 3), model units; 0 for no vertex.
// Use the whole model's V (not a region's) so that every view of one model classifies a vertex alike.
[[nodiscard]] double curvature_reference_length(const Eigen::MatrixXd& V);

// The |K| threshold of the sign rule, flat_band / L^2 (1/length^2); 0 when L is 0.
[[nodiscard]] double flat_curvature_threshold(double reference_length, double flat_band = kDefaultFlatBand);

// Sign of K per vertex: +1, -1, or 0 when |K_i| <= threshold or |angle_defect_i| <= kFlatAngleDefect.
// `threshold` normally comes from flat_curvature_threshold.
[[nodiscard]] std::vector<std::int8_t> curvature_signs(const GaussianCurvature& curvature, double threshold);

// Dihedral angles (between face normals, radians) at most this large count as coplanar for flat panels:
// above the ~1e-6 rad noise of float32 positions, below the facet angle of any tessellated curved surface
// whose curvature the sign rule would show.
inline constexpr double kCoplanarDihedral = 1e-3;
// Default crease angle for flat panels: the renderer's (build_render_model splits normals at 35 degrees).
inline constexpr double kDefaultCreaseAngle = 35.0 * std::numbers::pi / 180.0;

// Per face (#F): true when the face belongs to a flat panel, i.e. each of its edges is a boundary edge, a
// non-manifold edge, a crease (angle between the two face normals >= crease_angle, radians) or shared with
// a face whose normal is within kCoplanarDihedral of its own. Zero-area faces count as flat panels (they
// show nothing). Throws std::invalid_argument if F refers to a vertex outside V.
[[nodiscard]] std::vector<bool> flat_panel_faces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                 double crease_angle = kDefaultCreaseAngle);

// The signs to draw per vertex: vertex_signs (#V), but 0 at vertices all of whose faces are flat-panel faces
// (and at vertices of no face). A renderer whose vertices are split per panel applies the same rule per
// render vertex over the faces that use it.
[[nodiscard]] std::vector<std::int8_t> display_curvature_signs(const std::vector<std::int8_t>& vertex_signs,
                                                               const Eigen::MatrixXi& F,
                                                               const std::vector<bool>& flat_panel);

struct NormSummary {
  double rms = 0.0;  // sqrt(mean of squares) over the set
  double max = 0.0;  // largest magnitude over the set
  double l2 = 0.0;   // sqrt(sum of squares) over the set
};

struct DisplacementDecomposition {
  Eigen::VectorXd magnitude;   // #V, |u_i|
  Eigen::VectorXd along;       // #V, u_i . d^ (signed)
  Eigen::MatrixXd orthogonal;  // #V by 3, u_i - along_i d^
};

// u = V_after - V_before split along d (any non-zero vector; throws std::invalid_argument for a zero or
// non-finite d, or for V_before and V_after of different shapes).
[[nodiscard]] DisplacementDecomposition decompose_displacement(const Eigen::MatrixXd& V_before,
                                                               const Eigen::MatrixXd& V_after,
                                                               const Eigen::Vector3d& d);

// Norms of a per-vertex scalar (|value|) or per-vertex vector (row norm) over `vertices` (all if empty).
[[nodiscard]] NormSummary norms_over(const Eigen::VectorXd& values, std::span<const int> vertices);
[[nodiscard]] NormSummary row_norms_over(const Eigen::MatrixXd& rows, std::span<const int> vertices);

struct SectionCurve {
  std::vector<Eigen::Vector3d> points;  // ordered along the curve
  bool closed = false;                  // true: the last point connects back to the first (not repeated)
};

// The mesh cut by the plane {x : (x - origin) . n^ = 0}, n^ = normal / |normal|. A vertex exactly on the
// plane is treated as lying on its positive side, so every crossing lies strictly inside an edge and the
// curves are simple polylines. Curves come in no particular order. Throws std::invalid_argument for a zero
// normal.
[[nodiscard]] std::vector<SectionCurve> plane_section(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                      const Eigen::Vector3d& origin,
                                                      const Eigen::Vector3d& normal);

// The cut of V (plane_section) and the same surface points on a deformed copy V_carried (#V by 3, same
// faces): each point of the cut lies on an edge (a, b) at a parameter t of V, and its carried point is
// (1 - t) V_carried(a) + t V_carried(b). Curves and points correspond one to one.
struct CarriedSection {
  std::vector<SectionCurve> cut;      // plane_section(V, F, origin, normal)
  std::vector<SectionCurve> carried;  // the same surface points on V_carried
};
[[nodiscard]] CarriedSection plane_section_carried(const Eigen::MatrixXd& V, const Eigen::MatrixXd& V_carried,
                                                   const Eigen::MatrixXi& F, const Eigen::Vector3d& origin,
                                                   const Eigen::Vector3d& normal);

struct Section {
  double offset = 0.0;               // plane through origin + offset d^, normal d^
  std::vector<SectionCurve> before;  // the undeformed mesh cut
  std::vector<SectionCurve>
      after;  // the deformed mesh cut by the same plane (the paper's Fig. 13 silhouettes)
  // The surface points of `before` where the deformation took them (plane_section_carried; point for point
  // with `before`): the section of the material, which ASAN keeps rigid across d (the paper's section 4.3:
  // sections orthogonal to d stay as they were while the surface deforms along d). Seen along d, its
  // difference from `before` is the displacement across d of that section; a move along d does not show.
  std::vector<SectionCurve> carried;
};

struct MetricsOptions {
  double flat_band = kDefaultFlatBand;  // curvature sign rule: |K| L^2 <= flat_band is flat (dimensionless)
  // Raised bands for DeformationMetrics::reversals_by_band (dimensionless, like flat_band).
  std::vector<double> reversal_bands = {0.1, 1.0, 10.0};
  std::vector<double> section_offsets;  // offsets (model units) along d^ from section_origin
  Eigen::Vector3d section_origin = Eigen::Vector3d::Zero();
};

// Strict sign reversals among the vertices signed under a raised band before the pull (the header comment).
struct BandReversals {
  double band = 0.0;          // |K| L^2 <= band counts as flat (dimensionless)
  double radius_below = 0.0;  // L / sqrt(band): the curvature radius the band admits (model units)
  std::size_t compared = 0;   // interior vertices of S signed (not flat) under this band before the pull
  std::size_t reversals = 0;  // of those, signed the other way after it (under MetricsOptions::flat_band)
};

// Everything the paper evaluates for one push/pull, over a vertex set S (the region of interest).
struct DeformationMetrics {
  std::size_t evaluated_vertices = 0;   // |S|
  std::size_t curvature_vertices = 0;   // S minus mesh-boundary and non-manifold vertices: signs compared
  double reference_length = 0.0;        // L of the sign rule: bounding-box diagonal of `before` (model units)
  double curvature_threshold = 0.0;     // flat_band / L^2, 1/length^2: |K| at most this is flat
  std::size_t sign_flips = 0;           // vertices whose sign changed (any of +,-,0 to another)
  std::size_t sign_reversals = 0;       // strict reversals: + to - or - to + (the paper's sign changes)
  std::size_t into_flat = 0;            // + or - before, flat after
  std::size_t out_of_flat = 0;          // flat before, + or - after
  double sign_flip_fraction = 0.0;      // sign_flips / curvature_vertices (0 when there are none)
  double sign_reversal_fraction = 0.0;  // sign_reversals / curvature_vertices (0 when there are none)
  std::vector<BandReversals> reversals_by_band;  // one per MetricsOptions::reversal_bands entry
  std::size_t positive_before = 0, negative_before = 0, positive_after = 0, negative_after = 0;
  NormSummary displacement;       // |u| over S
  NormSummary along_d;            // |u . d^| over S
  NormSummary orthogonal;         // |u - (u . d^) d^| over S
  double mean_along_d = 0.0;      // signed mean of u . d^ over S
  std::vector<Section> sections;  // one per MetricsOptions::section_offsets entry
};

// Compares `before` with the same connectivity at positions V_after, over `vertices` (all if empty).
// Throws std::invalid_argument for shape mismatches, a zero d, out-of-range vertex indices, or a reversal
// band that is not positive and finite.
[[nodiscard]] DeformationMetrics evaluate_deformation(const Mesh& before, const Eigen::MatrixXd& V_after,
                                                      const Eigen::Vector3d& d, std::span<const int> vertices,
                                                      const MetricsOptions& options = {});

}  // namespace pushpull::deform
