// pushpull::deform metrics: the evaluation of Le Vaou et al. 2020 (section 5) as numbers.
//
//  - Discrete Gaussian curvature per vertex: the angle defect divided by the mixed Voronoi area
//    (Meyer, Desbrun, Schroeder, Barr 2003: Voronoi area for non-obtuse triangles, half / quarter of the
//    triangle area for obtuse ones). Interior vertex: defect 2 pi - sum of incident angles. Boundary vertex
//    (on an edge used by one face): defect pi - sum of angles (the discrete geodesic-curvature turn);
//    it is reported but excluded from sign statistics, since it measures the boundary curve, not the surface.
//  - Its sign, with a dead band: a vertex whose |K| is at most dead_band_fraction * max |K| (max over the
//    evaluated vertices of the mesh *before* deformation, so before and after use one threshold) counts as
//    zero (flat); the paper's yellow/blue sign maps become +1 / -1 / 0 here.
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
#include <span>
#include <vector>

#include "pushpull/deform/mesh.hpp"

namespace pushpull::deform {

struct GaussianCurvature {
  Eigen::VectorXd angle_defect;  // #V, radians (2 pi - sum angles inside, pi - sum angles on the boundary)
  Eigen::VectorXd area;          // #V, mixed Voronoi area
  Eigen::VectorXd K;             // #V, angle_defect / area (0 where the area is 0)
  std::vector<bool> boundary;    // #V, true on a boundary edge (an edge of exactly one face)
};

// Angle defect and mixed area per vertex. Degenerate faces contribute nothing. Throws std::invalid_argument
// if F refers to a vertex outside V.
[[nodiscard]] GaussianCurvature gaussian_curvature(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Angle defects at most this large (radians) are rounding noise: a flat vertex, whatever its area.
inline constexpr double kFlatAngleDefect = 1e-10;

// Sign of K per vertex: +1, -1, or 0 when |K_i| <= threshold or |angle_defect_i| <= kFlatAngleDefect.
[[nodiscard]] std::vector<std::int8_t> curvature_signs(const GaussianCurvature& curvature, double threshold);

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

struct Section {
  double offset = 0.0;               // plane through origin + offset d^, normal d^
  std::vector<SectionCurve> before;  // the undeformed mesh cut
  std::vector<SectionCurve> after;   // the deformed mesh cut by the same plane
};

struct MetricsOptions {
  double dead_band_fraction = 1e-3;     // curvature sign dead band, relative to max |K| before
  std::vector<double> section_offsets;  // offsets (model units) along d^ from section_origin
  Eigen::Vector3d section_origin = Eigen::Vector3d::Zero();
};

// Everything the paper evaluates for one push/pull, over a vertex set S (the region of interest).
struct DeformationMetrics {
  std::size_t evaluated_vertices = 0;  // |S|
  std::size_t curvature_vertices = 0;  // S minus mesh-boundary vertices: where signs are compared
  double curvature_threshold = 0.0;    // the dead band used, 1/length^2
  std::size_t sign_flips = 0;          // vertices whose sign changed (any of +,-,0 to another)
  std::size_t sign_reversals = 0;      // vertices that went + to - or - to + (no zero involved)
  double sign_flip_fraction = 0.0;     // sign_flips / curvature_vertices (0 when there are none)
  std::size_t positive_before = 0, negative_before = 0, positive_after = 0, negative_after = 0;
  NormSummary displacement;       // |u| over S
  NormSummary along_d;            // |u . d^| over S
  NormSummary orthogonal;         // |u - (u . d^) d^| over S
  double mean_along_d = 0.0;      // signed mean of u . d^ over S
  std::vector<Section> sections;  // one per MetricsOptions::section_offsets entry
};

// Compares `before` with the same connectivity at positions V_after, over `vertices` (all if empty).
// Throws std::invalid_argument for shape mismatches, a zero d, or out-of-range vertex indices.
[[nodiscard]] DeformationMetrics evaluate_deformation(const Mesh& before, const Eigen::MatrixXd& V_after,
                                                      const Eigen::Vector3d& d, std::span<const int> vertices,
                                                      const MetricsOptions& options = {});

}  // namespace pushpull::deform
