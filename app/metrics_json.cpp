// Serialises a `pushpull deform` run to the METRICS.json document described in metrics_json.hpp.
#include "metrics_json.hpp"

#include <nlohmann/json.hpp>

namespace pushpull::app {

namespace {

using json = nlohmann::ordered_json;  // keys in the order written: what was run, then results

json vec3(const Eigen::Vector3d& v) {
  return json::array({v.x(), v.y(), v.z()});
}

json norms(const deform::NormSummary& n) {
  return json{{"rms", n.rms}, {"max", n.max}, {"l2", n.l2}};
}

json curves(const std::vector<deform::SectionCurve>& list) {
  json out = json::array();
  for (const deform::SectionCurve& curve : list) {
    json points = json::array();
    for (const Eigen::Vector3d& p : curve.points) points.push_back(vec3(p));
    out.push_back(json{{"closed", curve.closed}, {"points", std::move(points)}});
  }
  return out;
}

}  // namespace

std::string metrics_json(const DeformRunRecord& record) {
  const deform::DeformResult& result = record.result;
  const deform::DeformationMetrics& metrics = record.metrics;
  const deform::DeformOptions& options = record.options;
  json doc;
  doc["input"] = record.input;
  doc["output"] = record.output;
  doc["life_size_scale"] = record.life_size_scale;
  doc["weld_tolerance"] = record.weld_tolerance;
  doc["method"] = std::string(deform::method_name(options.method));
  doc["asan_base"] = std::string(deform::method_name(options.asan_base));
  doc["mu"] = options.mu;
  doc["d"] = vec3(record.d);
  {
    json region;  // how the region was asked for (model units); null where not given
    region["handle_at"] = record.handle_at ? vec3(*record.handle_at) : json(nullptr);
    region["handle_radius"] = record.handle_at ? json(record.handle_radius) : json(nullptr);
    region["handle_file"] = record.handle_file.empty() ? json(nullptr) : json(record.handle_file);
    region["roi_radius"] = record.roi_radius ? json(*record.roi_radius) : json(nullptr);
    region["fixed_file"] = record.fixed_file.empty() ? json(nullptr) : json(record.fixed_file);
    doc["region"] = region;
  }
  doc["units"] = {
      {"lengths", "model units (life_size_scale metres each)"},
      {"error_estimate", "fraction of |d|"},
      {"curvature_threshold", "1 / model unit^2 (Gaussian curvature)"},
      {"section_offset",
       "the section's plane: p . d / |d| = offset (model units, measured from the model's origin)"},
      {"times", "milliseconds"}};
  doc["stretch_direction"] = options.stretch_direction ? vec3(*options.stretch_direction) : json(nullptr);
  doc["sr_arap_alpha"] = options.sr_arap_alpha;
  doc["arap_h_lambda"] = options.arap_h_lambda;
  doc["arap_n_rings"] = options.arap_n_rings;
  doc["vertices"] = record.vertices;
  doc["roi_vertices"] = record.handle_count + record.fixed_count + record.free_count;
  doc["handle_count"] = record.handle_count;
  doc["fixed_count"] = record.fixed_count;
  doc["free_count"] = record.free_count;
  doc["iterations"] = result.iterations;
  doc["max_iterations"] = options.max_iterations;
  doc["tolerance"] = options.tolerance;
  doc["energy_tolerance"] = options.energy_tolerance;
  doc["anderson"] = options.anderson_window;
  // Cold solves of regions with at least this many free vertices start from the biharmonic spread (-1:
  // never); smooth_start: this one did.
  doc["smooth_start_min_free"] = options.smooth_start_min_free;
  doc["smooth_start"] = result.smooth_start;
  // Likewise the coarse-to-fine start; coarse_evaluations: the local-global steps of its coarse solve.
  doc["coarse_start_min_free"] = options.coarse_start_min_free;
  doc["coarse_start"] = result.coarse_start;
  doc["coarse_evaluations"] = result.coarse_evaluations;
  doc["converged"] = result.converged;
  doc["stop_reason"] = std::string(deform::stop_reason_name(result.stop_reason));
  // Estimated largest vertex distance to the exact minimiser, relative to |d| (null before it is known).
  doc["error_estimate"] = result.error_estimate ? json(*result.error_estimate) : json(nullptr);
  // The rate behind it, the rate of the last iterations (a warm start's hint), and the rate probe of an early
  // stop (deformer.hpp: probe_rate) with its extra local-global steps (null and 0 when it did not run).
  doc["estimate_rate"] = result.estimate_rate ? json(*result.estimate_rate) : json(nullptr);
  doc["contraction_rate"] = result.contraction_rate ? json(*result.contraction_rate) : json(nullptr);
  doc["probe_rate"] = result.probe_rate ? json(*result.probe_rate) : json(nullptr);
  doc["probe_evaluations"] = result.probe_evaluations;
  doc["initial_energy"] = result.initial_energy;
  doc["energy_trace"] = result.energy_trace;
  doc["timing_ms"] = json{{"precompute", result.timing.precompute},
                          {"factorize", result.timing.factorize},
                          {"solve", result.timing.solve},
                          {"per_iteration", result.timing.per_iteration},
                          {"total", record.total_ms}};
  doc["max_displacement"] = metrics.displacement.max;
  doc["gaussian_sign_flip_fraction"] = metrics.sign_flip_fraction;
  doc["gaussian_sign_reversal_fraction"] = metrics.sign_reversal_fraction;
  doc["along_d_norm"] = metrics.along_d.rms;
  doc["orthogonal_norm"] = metrics.orthogonal.rms;
  doc["norm"] = "rms over the ROI vertices (see norms for max and l2)";
  doc["norms"] = json{{"displacement", norms(metrics.displacement)},
                      {"along_d", norms(metrics.along_d)},
                      {"orthogonal", norms(metrics.orthogonal)}};
  doc["mean_along_d"] = metrics.mean_along_d;
  json by_band = json::array();
  for (const deform::BandReversals& band : metrics.reversals_by_band)
    by_band.push_back(json{{"band", band.band},
                           {"radius_below", band.radius_below},
                           {"compared", band.compared},
                           {"reversals", band.reversals}});
  doc["curvature"] = json{
      {"evaluated_vertices", metrics.curvature_vertices},
      {"threshold", metrics.curvature_threshold},
      {"dead_band_fraction", record.dead_band_fraction},
      {"sign_flips", metrics.sign_flips},
      {"sign_reversals", metrics.sign_reversals},
      {"positive_before", metrics.positive_before},
      {"negative_before", metrics.negative_before},
      {"positive_after", metrics.positive_after},
      {"negative_after", metrics.negative_after},
      {"area", "mixed Voronoi (Meyer et al. 2003)"},
      {"boundary", "vertices on the mesh boundary or a non-manifold edge excluded"},
      {"flat_band", record.dead_band_fraction},
      {"reference_length", metrics.reference_length},
      {"into_flat", metrics.into_flat},
      {"out_of_flat", metrics.out_of_flat},
      {"sign_reversal_fraction", metrics.sign_reversal_fraction},
      {"reversals_by_band", by_band},
      {"flat_rule",
       "|K| * reference_length^2 <= flat_band (reference_length: bounding-box diagonal of the "
       "model); sign_flips counts every change, sign_reversals only + to - and - to +; "
       "reversals_by_band: the reversals again among the vertices signed before the pull with "
       "flat_band raised to band (curvature radius below radius_below: compared), signed the other way "
       "after it under flat_band; vertices on the mesh boundary or a non-manifold edge are left out; "
       "evaluated_vertices: the region's vertices whose signs were compared (the fractions' denominator; "
       "the region's size is roi_vertices); dead_band_fraction: flat_band under its earlier name"}};
  json sections = json::array();
  for (const deform::Section& section : metrics.sections) {
    sections.push_back(json{{"offset", section.offset},
                            {"before", curves(section.before)},
                            {"after", curves(section.after)},
                            {"carried", curves(section.carried)}});
  }
  doc["sections"] = std::move(sections);
  json parts = json::array();
  for (const AttachedPartRecord& part : record.attached) {
    parts.push_back({{"component", part.component}, {"vertices", part.vertex_count},
                     {"first_vertex", part.first_vertex}, {"rest_gap", part.rest_gap},
                     {"max_displacement", part.max_displacement}});
  }
  doc["attached_parts"] = {{"reach", record.attach_reach}, {"parts", parts}};
  doc["warnings"] = result.warnings;
  // (replace: a path that is not UTF-8 is written with U+FFFD, not thrown on after the work is done)
  return doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace pushpull::app
