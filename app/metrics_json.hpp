// The METRICS.json document written by `pushpull deform`: what was run, how the solver behaved, and the
// paper's evaluation numbers (pushpull::deform::DeformationMetrics).
//
// Keys (lengths in model units, i.e. the file's units; times in milliseconds):
//   input, output, life_size_scale (metres per model unit), method, asan_base, mu, d [3], stretch_direction
//   [3] | null, vertices, roi_vertices, handle_count, fixed_count, free_count, iterations, max_iterations,
//   tolerance, energy_tolerance, anderson, converged, stop_reason, energy_trace [..], initial_energy,
//   timing_ms {precompute, factorize, solve, per_iteration, total},
//   max_displacement, gaussian_sign_flip_fraction (any sign change), gaussian_sign_reversal_fraction (+ to -
//   and - to + only), along_d_norm (RMS over the ROI), orthogonal_norm (RMS),
//   norms {displacement, along_d, orthogonal: {rms, max, l2}}, mean_along_d,
//   curvature {evaluated_vertices, threshold, dead_band_fraction, sign_flips, sign_reversals,
//              positive_before, negative_before, positive_after, negative_after, area: "mixed Voronoi",
//              boundary: "excluded", flat_band, reference_length, into_flat, out_of_flat,
//              sign_reversal_fraction, reversals_by_band [{band, radius_below, compared, reversals}],
//              flat_rule: text}. Flat: |K| reference_length^2 <= flat_band (the
//              deform sign rule, metrics.hpp); dead_band_fraction repeats flat_band for older readers
//              (it no longer is a fraction of max |K|).
//   sections [{offset, before: [{closed, points [[x,y,z]..]}], after: [...]}],
//   attached_parts {reach, parts: [{component, vertices, first_vertex, rest_gap, max_displacement}]},
//   warnings [..].
// Thread-safety: free functions without state.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "pushpull/assets/weld.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/metrics.hpp"

namespace pushpull::app {

// A separate part (component) that followed the solved surface.
struct AttachedPartRecord {
  int component = -1;
  long vertex_count = 0;
  int first_vertex = -1;
  double rest_gap = 0.0;          // distance to the region at rest
  double max_displacement = 0.0;  // largest move of its vertices
};

struct DeformRunRecord {
  std::string input;                            // model file read
  std::string output;                           // deformed model written
  deform::DeformOptions options;                // as passed to the solver (progress callback unused)
  Eigen::Vector3d d = Eigen::Vector3d::Zero();  // push/pull displacement, model units
  long vertices = 0;                            // #V of the model
  long handle_count = 0, fixed_count = 0, free_count = 0;
  double total_ms = 0.0;  // deform: wall time of the command, load to write; replay: the commit's solve
  deform::DeformResult result;
  deform::DeformationMetrics metrics;
  double dead_band_fraction = 0.0;  // the sign rule's flat band (--dead-band), dimensionless
  // The load's weld, relative to the bounding-box diagonal (--weld-tolerance).
  double weld_tolerance = assets::WeldOptions{}.relative_tolerance;
  std::vector<AttachedPartRecord> attached;  // parts that follow the surface (empty when turned off)
  double attach_reach = 0.0;                 // the distance that decided which parts follow
  double life_size_scale = 1.0;  // metres per model unit (--scale / --length)
  // How the region was asked for (deform's options; model units), so that the run can be repeated from its
  // metrics: --handle-at and --handle-radius, or the --handle file; --roi-radius and the --fixed file.
  std::optional<Eigen::Vector3d> handle_at;
  double handle_radius = 0.0;
  std::optional<double> roi_radius;
  std::string handle_file, fixed_file;
};

// The JSON text (pretty-printed, trailing newline).
[[nodiscard]] std::string metrics_json(const DeformRunRecord& record);

}  // namespace pushpull::app
