// `pushpull deform`: one push/pull on a model in batch, writing the deformed model and METRICS.json.
#include "band_reversals_text.hpp"
#include "commands.hpp"
#include "drag_notes.hpp"
#include "life_size.hpp"
#include "messages_off_stdout.hpp"
#include "method_check.hpp"
#include "metrics_json.hpp"
#include "model_output.hpp"
#include "number_checks.hpp"
#include "output_guard.hpp"
#include "point_text.hpp"
#include "region_notes.hpp"
#include "signals_held.hpp"
#include "vertex_selection.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/assets/write.hpp"
#include "pushpull/deform/attached_parts.hpp"
#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/file_output.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/deform/roi.hpp"
#include "pushpull/deform/surface_point.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

namespace {

namespace fs = std::filesystem;

struct DeformCommandOptions {
  std::string mesh;
  double weld_tolerance = assets::WeldOptions{}.relative_tolerance;  // of the bounding-box diagonal
  std::string handle_file;
  std::string fixed_file;
  std::vector<double> handle_at;
  double handle_radius = 0.0;
  std::vector<double> displacement;
  std::string method = "asan";
  double mu = 100.0;
  int iterations = deform::DeformOptions{}.max_iterations;
  double tolerance = deform::DeformOptions{}.tolerance;
  bool paper_iterations = false;
  std::optional<double> energy_tolerance;
  std::optional<int> anderson;  // unset: the solver's default window
  std::optional<int> smooth_start_min_free;  // unset: the solver's default
  std::optional<int> coarse_start_min_free;  // unset: the solver's default
  std::optional<double> roi_radius;
  std::vector<double> stretch_direction;
  std::string asan_base = "arap-sr";
  double alpha = 0.02;
  double lambda = 1.0;
  int rings = 2;
  int sections = 5;
  double dead_band = deform::kDefaultFlatBand;
  bool attached_parts = true;
  double attach_reach = 0.0;  // <= 0: automatic
  std::string out;
  std::string metrics;
  LifeSizeOptions life_size;  // the lengths above are typed in life-size metres
};

// --- model loading and saving: the two places that know file formats ---------------------------------
// Every format goes through pushpull::assets, which welds the file's patches into one surface (the mesh the
// solver sees, in model/world coordinates: --handle-at points are in that frame), as the headset review
// does: a tessellated CAD model's patches, their seam vertices written once per patch, deform as one surface
// instead of tearing apart. --handle/--fixed files of an OFF/OBJ/PLY name the file's own vertices
// (read_model_index_file). The model is kept so that the output carries what the file held (model_output).

struct LoadedModel {
  std::shared_ptr<const deform::Mesh> mesh;  // what the solver deforms: the welded surface
  assets::Model scene;                       // the model as loaded (the weld's map, a glTF's scene)
};

LoadedModel load_model(const fs::path& path, double weld_tolerance) {
  if (!fs::exists(path)) throw CommandError(path.string() + ": model file does not exist");
  if (!assets::is_supported_model_path(path)) {
    throw CommandError(path.string() +
                       ": unsupported model format (expected .gltf, .glb, .drc, .off, .obj or .ply)");
  }
  try {
    assets::LoadOptions load;
    load.weld.relative_tolerance = weld_tolerance;
    assets::Model scene = assets::load_model(path, load);
    auto mesh = std::make_shared<const deform::Mesh>(scene.deform_mesh);
    return {std::move(mesh), std::move(scene)};
  } catch (const assets::AssetError& error) {
    throw CommandError(error.what());
  }
}

void check_output_model_path(const fs::path& path) {
  if (!deform::mesh_format_from_path(path) && !is_glb_path(path)) {
    throw CommandError(path.string() + ": unsupported output format (expected .glb, .off, .obj or .ply)");
  }
}

// V: #V by 3 deformed positions of model.mesh.
// ------------------------------------------------------------------------------------------------------

// The lengths typed on the command line (life-size metres, see life_size.hpp) in the model's file units.
void convert_to_file_units(DeformCommandOptions& o, const LifeSize& life) {
  o.handle_at = life.to_file_units(o.handle_at);
  o.handle_radius = life.to_file_units(o.handle_radius);
  if (o.roi_radius) o.roi_radius = life.to_file_units(*o.roi_radius);
  o.attach_reach = life.to_file_units(o.attach_reach);
  o.displacement = life.to_file_units(o.displacement);
}

Eigen::Vector3d vector3(const std::vector<double>& values, const char* option) {
  const Eigen::Vector3d v(values.at(0), values.at(1), values.at(2));
  if (!v.allFinite()) throw CommandError(std::string(option) + ": values must be finite numbers");
  return v;
}

deform::Method parse_method_or_throw(const std::string& name, const char* option) {
  try {
    return deform::parse_method(name);
  } catch (const std::invalid_argument& error) {
    throw CommandError(std::string(option) + ": " + error.what());
  }
}

// --handle-at P --handle-radius R: the surface point closest to P, then every vertex within R of it along
// the surface (on that point's component only), the rule the headset uses for a ray hit.
// o is in file units (convert_to_file_units); `scale` (metres per file unit) puts the message back in the
// life-size metres the user typed.
// `notes`, when given, receives warnings about the handle (a handle far from the point asked for); `source`,
// when given, where it came from (the --handle file and the numbers it wrote).
std::vector<int> pick_handle(const DeformCommandOptions& o, const LoadedModel& model, double scale,
                             std::vector<std::string>* notes = nullptr, SelectionSource* source = nullptr) {
  const deform::Mesh& mesh = *model.mesh;
  if (!o.handle_file.empty()) {
    std::size_t unused = 0;
    std::vector<int> named;
    std::vector<int> handle = read_model_index_file(o.handle_file, model.scene, &unused, &named);
    if (source) *source = {o.handle_file, std::move(named)};
    if (unused > 0 && notes != nullptr)
      notes->push_back(o.handle_file + ": " + std::to_string(unused) +
                       " of its vertices are used by no triangle of the model: left out of the handle");
    return handle;
  }
  const Eigen::Vector3d point = vector3(o.handle_at, "--handle-at");
  {
    // A point a million model sizes away is a typing slip (units, an exponent); its nearest surface point is
    // not even computable where the squared distances overflow.
    const Eigen::Vector3d low = mesh.V.colwise().minCoeff(), high = mesh.V.colwise().maxCoeff();
    const double across = (high - low).norm();
    const double away = (point - point.cwiseMax(low).cwiseMin(high)).stableNorm();
    if (away > 1e6 * std::max(across, std::numeric_limits<double>::min())) {
      char text[192];
      std::snprintf(
          text, sizeof text,
          "--handle-at %.6g %.6g %.6g is %.3g m from the model's bounding box, over a million times its "
          "size (%.3g m across): a point on or near the surface is expected",
          point.x() * scale, point.y() * scale, point.z() * scale, away * scale, across * scale);
      throw CommandError(o.mesh + ": " + text);
    }
  }
  deform::SurfacePoint hit;
  try {
    hit = deform::closest_surface_point(mesh, point);
  } catch (const std::invalid_argument& error) {
    throw CommandError(o.mesh + ": " + error.what());
  }
  const double gap = (hit.point - point).stableNorm();
  if (gap > o.handle_radius) {
    auto metres = [&](const Eigen::Vector3d& p) { return point_in_metres_text(p * scale); };
    char numbers[128];
    std::snprintf(numbers, sizeof numbers, "%.6g m from the surface, farther than --handle-radius %.6g m",
                  gap * scale, o.handle_radius * scale);
    throw CommandError(o.mesh + ": --handle-at " + metres(point) + " is " + numbers +
                       "; the nearest surface point is --handle-at " + metres(hit.point) +
                       (scale != 1.0 ? " (life-size metres)" : ""));
  }
  std::vector<int> handle = deform::surface_handle(mesh, hit, o.handle_radius);
  // No vertex within the radius (large triangles): the handle is the hit triangle's nearest corner, wherever
  // it is; said, with how far, since a push/pull there is a spike at that corner.
  if (handle.size() == 1 && notes != nullptr) {
    const double away = (mesh.V.row(handle[0]).transpose() - hit.point).norm();
    if (away > o.handle_radius) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "no vertex lies within --handle-radius %.6g m of the surface point: the handle is the "
                    "nearest corner of its triangle, vertex %d, %.3g m away (a larger --handle-radius "
                    "takes more of the surface)",
                    o.handle_radius * scale, handle[0], away * scale);
      notes->push_back(text);
    }
  }
  return handle;
}

deform::DeformOptions solver_options(const DeformCommandOptions& o) {
  deform::DeformOptions options;
  options.method = parse_method_or_throw(o.method, "--method");
  options.asan_base = parse_method_or_throw(o.asan_base, "--asan-base");
  options.mu = o.mu;
  if (!o.stretch_direction.empty()) {
    options.stretch_direction = vector3(o.stretch_direction, "--stretch-direction");
    if (options.stretch_direction->stableNorm() == 0.0)
      throw UsageError("--stretch-direction: must not be zero");
  }
  options.max_iterations = o.iterations;
  options.tolerance = o.tolerance;  // --tolerance 0 (and no --energy-tolerance): exactly --iterations
  options.energy_tolerance = o.energy_tolerance.value_or(options.energy_tolerance);
  if (o.anderson) options.anderson_window = *o.anderson;
  if (o.smooth_start_min_free) options.smooth_start_min_free = *o.smooth_start_min_free;
  if (o.coarse_start_min_free) options.coarse_start_min_free = *o.coarse_start_min_free;
  if (o.paper_iterations) options = deform::paper_iterations(options);
  options.sr_arap_alpha = o.alpha;
  options.arap_h_lambda = o.lambda;
  options.arap_n_rings = o.rings;
  return options;
}

std::string tolerance_text(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

// Why the solver stopped, with the tolerance that stopped it and whether the user set it.
std::string stop_text(deform::StopReason reason, const DeformCommandOptions& o,
                      const deform::DeformOptions& options) {
  std::string text(deform::stop_reason_name(reason));
  if (reason == deform::StopReason::ErrorTolerance)
    text += ": estimated distance to the minimiser <= " + tolerance_text(options.tolerance) + " |d|";
  else if (reason == deform::StopReason::EnergyTolerance)
    text += " " + tolerance_text(options.energy_tolerance) + (o.energy_tolerance ? "" : ", the default");
  if (o.paper_iterations) text += "; as in the paper, not converged";
  return text;
}

// A length in mm with `decimals` decimals, or three significant digits below what they show (a 5 um pull is
// "0.005 mm", not "0.0 mm").
// Beyond a kilometre, four significant digits (not 300 of them).
std::string mm_text(double mm, int decimals) {
  char text[48];
  if (std::abs(mm) >= 1e6 || !std::isfinite(mm))
    std::snprintf(text, sizeof text, "%.4g mm", mm);
  else if (mm != 0.0 && std::abs(mm) < std::pow(10.0, -decimals) * 10.0)
    std::snprintf(text, sizeof text, "%.3g mm", mm);
  else
    std::snprintf(text, sizeof text, "%.*f mm", decimals, mm);
  return text;
}

// The solver's estimate of its distance to the exact minimiser, in mm at life size and relative to |d|.
std::string error_text(const deform::DeformResult& r, const Eigen::Vector3d& d, const LifeSize& life) {
  if (!r.error_estimate) return "not yet available";
  char text[32];
  std::snprintf(text, sizeof(text), " (%.1e |d|)", *r.error_estimate);
  return mm_text(life.to_mm(*r.error_estimate * d.norm()), 2) + text;
}

// Section planes spread evenly across the ROI's extent along d.
std::vector<double> section_offsets(const deform::Mesh& mesh, const std::vector<int>& roi,
                                    const Eigen::Vector3d& d, int count) {
  if (count <= 0 || roi.empty()) return {};
  const Eigen::Vector3d unit = d.normalized();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const int i : roi) {
    const double s = mesh.V.row(i).dot(unit);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  std::vector<double> offsets;
  for (int k = 1; k <= count; ++k) offsets.push_back(lo + (hi - lo) * k / (count + 1));
  return offsets;
}

// The smallest pull solved, relative to the model's bounding-box diagonal.
constexpr double kSmallestPull = 1e-10;
// A region vertex that moved more than this many times |d| makes the result suspect (warned).
constexpr double kFarMove = 10.0;

void run_deform(DeformCommandOptions o) {
  const auto start = std::chrono::steady_clock::now();
  (void)messages_off_stdout({o.out, o.metrics});
  if (o.handle_file.empty() == o.handle_at.empty()) {
    throw UsageError("give exactly one of --handle FILE or --handle-at X Y Z (with --handle-radius)");
  }
  if (!o.handle_at.empty() && !(o.handle_radius > 0.0))
    throw UsageError("--handle-at needs a positive --handle-radius");
  if (o.fixed_file.empty() && !o.roi_radius) {
    throw UsageError("give --fixed FILE, --roi-radius R, or both (the region needs a boundary)");
  }
  if (vector3(o.displacement, "--displacement").norm() == 0.0)
    throw UsageError("--displacement: zero displacement (nothing to push or pull)");
  deform::DeformOptions options = solver_options(o);
  check_output_model_path(o.out);
  // Every output is checked before any is written, so a bad one leaves the others as they were.
  for (const auto& [option, output] : {std::pair{"--out", &o.out}, std::pair{"--metrics", &o.metrics}})
    if (const std::string problem = deform::output_path_problem(*output); !problem.empty())
      throw CommandError((output->empty() ? std::string(option) : *output) + ": " + problem);
  if (deform::same_output_file(o.out, o.metrics))
    throw UsageError("--out and --metrics name the same file (" + o.out +
                     "): the metrics would replace the model");

  const LoadedModel model = load_model(o.mesh, o.weld_tolerance);
  {
    std::vector<InputFile> inputs = model_inputs(model.scene.source_files);
    if (!o.handle_file.empty()) inputs.push_back({o.handle_file, "the --handle file"});
    if (!o.fixed_file.empty()) inputs.push_back({o.fixed_file, "the --fixed file"});
    refuse_output_over_inputs("--out", o.out, inputs);
    refuse_output_over_inputs("--metrics", o.metrics, inputs);
  }
  const std::shared_ptr<const deform::Mesh>& mesh = model.mesh;
  const LifeSize life(o.life_size, bounds_of(mesh->V), o.mesh);
  convert_to_file_units(o, life);
  const Eigen::Vector3d d = vector3(o.displacement, "--displacement");
  {
    // A pull many times the model's size is a typing slip (units, an exponent), not a push/pull: refused
    // before it overflows the solver's numbers.
    const double across = (mesh->V.colwise().maxCoeff() - mesh->V.colwise().minCoeff()).norm();
    if (across > 0.0 && !(d.norm() <= 100.0 * across)) {
      char text[192];
      std::snprintf(text, sizeof text,
                    "--displacement: |d| = %.6g m is more than 100 times the model's size (%.6g m across)",
                    d.stableNorm() * life.scale(), across * life.scale());
      throw CommandError(text);
    }
    // So is one below what the model's coordinates resolve: on a 2 m model a pull of 1e-11 m came out 7% of
    // |d| off with an estimate of 0 (rounding, not the solver's iterations, sets the error there).
    if (across > 0.0 && d.stableNorm() < kSmallestPull * across) {  // (stable: its square may underflow)
      char text[224];
      std::snprintf(
          text, sizeof text,
          "--displacement: |d| = %.3g m is less than %.0e times the model's size (%.6g m across): too "
          "small for its coordinates' precision",
          d.stableNorm() * life.scale(), kSmallestPull, across * life.scale());
      throw CommandError(text);
    }
  }
  std::vector<std::string> handle_notes;
  SelectionSource handle_source, fixed_source{o.fixed_file, {}};
  const std::vector<int> handle = pick_handle(o, model, life.scale(), &handle_notes, &handle_source);
  std::size_t unused_fixed = 0;
  const std::vector<int> fixed =
      o.fixed_file.empty()
          ? std::vector<int>{}
          : read_model_index_file(o.fixed_file, model.scene, &unused_fixed, &fixed_source.file_vertices);
  if (unused_fixed > 0)
    handle_notes.push_back(o.fixed_file + ": " + std::to_string(unused_fixed) +
                           " of its vertices are used by no triangle of the model: left out");

  // A vertex both held and pulled, named as the user numbered it (the file's vertices, which the weld may
  // have made one point) rather than by the welded surface's number.
  std::vector<int> both;
  std::set_intersection(handle.begin(), handle.end(), fixed.begin(), fixed.end(), std::back_inserter(both));
  if (!both.empty())
    throw CommandError(shared_vertex_message(model.scene, both, handle_source, fixed_source));

  deform::RegionOfInterest roi;
  try {
    roi = deform::build_roi(*mesh, handle, fixed,
                            o.roi_radius.value_or(std::numeric_limits<double>::infinity()));
  } catch (const std::invalid_argument& error) {
    const std::string what = error.what();  // (build_roi may name the region itself)
    throw CommandError(what.rfind("region of interest", 0) == 0 ? what : "region of interest: " + what);
  }
  // No border holds the part (the region covers the whole connected part): it moves with the handle as a
  // whole, as a push/pull on it does in the headset (drag_notes.cpp); said, not refused. No border and not a
  // whole part: the region is the handle alone (--roi-radius 0), torn from the surface around it.
  const std::optional<UnheldRegion> unheld = unheld_region(roi);

  DeformRunRecord record;
  if (!o.handle_at.empty()) {
    record.handle_at = vector3(o.handle_at, "--handle-at");
    record.handle_radius = o.handle_radius;
  }
  record.handle_file = o.handle_file;
  record.fixed_file = o.fixed_file;
  record.roi_radius = o.roi_radius;
  try {
    deform::Deformer deformer(mesh, roi, options);
    record.result = deformer.solve(d);
  } catch (const std::invalid_argument& error) {
    throw CommandError(o.mesh + ": " + error.what());
  }
  // Not converged (the paper's setting says so in its stop text): a warning too, for scripts that read them.
  if (!record.result.converged && !o.paper_iterations) {
    char text[320];
    // (No rate probe checks a stop at the cap: adversarial pulls stopped there were up to 2.5x over it.)
    if (record.result.error_estimate)
      std::snprintf(text, sizeof text,
                    "not converged: stopped after %d iteration(s) (%s) with the estimated distance to the "
                    "minimiser %.2g |d|, above --tolerance %.2g (an unchecked estimate: it can be 2-3x low)",
                    record.result.iterations,
                    std::string(deform::stop_reason_name(record.result.stop_reason)).c_str(),
                    *record.result.error_estimate, options.tolerance);
    else
      std::snprintf(
          text, sizeof text, "not converged: stopped after %d iteration(s) (%s) without a distance estimate",
          record.result.iterations, std::string(deform::stop_reason_name(record.result.stop_reason)).c_str());
    record.result.warnings.push_back(text);
  }
  // A surface that moved many times farther than the handle is no push/pull: a parameter far from its range
  // (arap-h's --lambda 1e12 moved the bonnet 316 m on a 100 mm pull, exit 0 and only "not converged" said).
  {
    double farthest = 0.0;
    for (const std::vector<int>* part : {&roi.free, &roi.handle})
      for (const int v : *part)
        farthest = std::max(farthest, (record.result.V.row(v) - mesh->V.row(v)).norm());
    if (farthest > kFarMove * d.norm()) {
      const char* hint = options.method == deform::Method::ArapH || options.method == deform::Method::ArapSrH
                             ? " (a smaller --lambda weighs the curvature term less)"
                         : options.method == deform::Method::SrArap ? " (try a smaller --alpha)"
                         : options.method == deform::Method::Asan   ? " (try the paper's --mu 100)"
                                                                    : "";
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%.3g", farthest / d.norm());
      record.result.warnings.push_back("the surface moved up to " + mm_text(life.to_mm(farthest), 1) + ", " +
                                       ratio + " times |d| = " + mm_text(life.to_mm(d.norm()), 1) +
                                       ": far more than the pull, not a push/pull result" + hint);
    }
  }
  if (unheld) {
    record.result.warnings.insert(
        record.result.warnings.begin(),
        unheld_region_text(*unheld) + (*unheld == UnheldRegion::WholePart
                                           ? " (give --fixed or a smaller --roi-radius to hold it)"
                                           : " (give a --roi-radius that reaches past the handle)"));
  }
  // Held, but with nothing between the handle and the fixed vertices to give: the handle steps out alone.
  if (roi.free.empty() && !roi.fixed.empty() && !roi.handle.empty())
    record.result.warnings.insert(
        record.result.warnings.begin(),
        "only the handle moves: no free vertex lies between it and the fixed ones, so "
        "it steps out of the surface (a larger --roi-radius gives the region room)");
  for (const std::string& note : handle_notes)
    record.result.warnings.insert(record.result.warnings.begin(), note);
  // What the load noticed (an unsupported extension the file requires, parts it ignored): said here too, as
  // `pushpull info` says it.
  {
    const std::vector<std::string> load_warnings = assets::warnings_naming_the_file(model.scene);
    record.result.warnings.insert(record.result.warnings.begin(), load_warnings.begin(), load_warnings.end());
  }
  // The review's readout says it of a pull over kSteepPull handle radii; so does deform.
  if (!o.handle_at.empty())
    if (const auto steep = steep_pull_warning(d.norm(), o.handle_radius))
      record.result.warnings.insert(record.result.warnings.begin(), *steep);
  // Parts on the solved surface (lamps, plates, trims) follow it; the metrics below stay those of the region.
  if (o.attached_parts) {
    const deform::AttachedParts parts(*mesh, roi, {.reach = o.attach_reach});
    Eigen::MatrixXd before = record.result.V;
    parts.apply(record.result.V);
    for (const deform::AttachedPart& part : parts.parts()) {
      double moved = 0.0;
      for (int v : part.vertices) moved = std::max(moved, (record.result.V.row(v) - before.row(v)).norm());
      record.attached.push_back({part.component, static_cast<long>(part.vertices.size()), part.vertices.front(),
                                 part.rest_gap, moved});
    }
    record.attach_reach = parts.reach();
  }
  std::vector<int> omega;
  omega.reserve(roi.size());
  omega.insert(omega.end(), roi.handle.begin(), roi.handle.end());
  omega.insert(omega.end(), roi.fixed.begin(), roi.fixed.end());
  omega.insert(omega.end(), roi.free.begin(), roi.free.end());
  std::sort(omega.begin(), omega.end());

  deform::MetricsOptions metrics_options;
  metrics_options.flat_band = o.dead_band;
  metrics_options.section_offsets = section_offsets(*mesh, omega, d, o.sections);
  record.metrics = deform::evaluate_deformation(*mesh, record.result.V, d, omega, metrics_options);

  // The model and its metrics are written as a pair: Ctrl-C or SIGTERM between them is acted on after both
  // (signals_held.hpp).
  std::optional<SignalsHeld> pair_written;
  pair_written.emplace();
  for (std::string& warning : write_deformed_model(o.out, o.mesh, *model.mesh, &model.scene, record.result.V))
    record.result.warnings.push_back(std::move(warning));

  record.input = o.mesh;
  record.output = o.out;
  record.options = options;
  record.d = d;
  record.vertices = static_cast<long>(mesh->vertex_count());
  record.handle_count = static_cast<long>(roi.handle.size());
  record.fixed_count = static_cast<long>(roi.fixed.size());
  record.free_count = static_cast<long>(roi.free.size());
  record.dead_band_fraction = o.dead_band;
  record.weld_tolerance = o.weld_tolerance;
  record.life_size_scale = life.scale();
  record.total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  try {
    deform::write_file_atomically(o.metrics, metrics_json(record));
  } catch (const std::exception& error) {  // the model is written by now: said, as it is on disk
    throw CommandError(std::string(error.what()) + " (the deformed model was written to " + o.out + ")");
  }
  pair_written.reset();

  const deform::DeformResult& r = record.result;
  const deform::DeformationMetrics& m = record.metrics;
  std::printf("pushpull deform: %s, %s, |d| = %s, ROI %zu of %ld vertices (%zu handle, %zu fixed)\n",
              o.mesh.c_str(), o.method.c_str(), mm_text(life.to_mm(d.norm()), 1).c_str(), omega.size(),
              record.vertices, roi.handle.size(), roi.fixed.size());
  if (life.scale() != 1.0)
    std::printf(
        "  life size: %g m per file unit (lengths typed and printed at life size; files keep file units)\n",
        life.scale());
  // The weld joined the file's patches (their seams' vertices, written once per patch, are one vertex each):
  // counts above and in the metrics are of the welded surface.
  if (const assets::WeldStats& weld = model.scene.report.weld; weld.deform_vertices < weld.render_vertices)
    std::printf(
        "  welded: %zu vertices of the file's triangles -> %zu (%zu pieces -> %zu component%s), as "
        "`pushpull info` reports; %s\n",
        weld.render_vertices, weld.deform_vertices, weld.pieces_before, weld.topology.components,
        weld.topology.components == 1 ? "" : "s",
        index_files_name_file_vertices(model.scene)
            ? "counts and vertex numbers here and in the metrics are the welded surface's, index files and "
              "the output keep the file's numbering"
            : "counts and vertex numbers here, in the metrics and in index files are the welded surface's");
  std::printf("  %d iterations, %s (%s); estimated error %s; %.1f ms per iteration, %.1f ms factorize, %.1f ms "
              "total\n",
              r.iterations, r.converged ? "converged" : "not converged",
              stop_text(r.stop_reason, o, options).c_str(), error_text(r, d, life).c_str(), r.timing.per_iteration,
              r.timing.factorize, record.total_ms);
  if (r.smooth_start)
    std::printf(
        "  started from the handle's move spread biharmonically over the region (asan, at least %d free "
        "vertices: --smooth-start-min-free)\n",
        options.smooth_start_min_free);
  if (r.coarse_start)
    std::printf(
        "  started coarse-to-fine: solved first on a coarser tessellation of the region (%d local-global "
        "steps there; asan, at least %d free vertices: --coarse-start-min-free)\n",
        r.coarse_evaluations, options.coarse_start_min_free);
  if (r.probe_rate)
    std::printf(
        "  rate probe (an early stop checked): %d extra local-global steps, slowest rate found %.5f; the "
        "estimate rests on %.5f\n",
        r.probe_evaluations, *r.probe_rate, r.estimate_rate.value_or(NAN));
  std::printf("  max displacement %.2f mm; RMS along d %.2f mm, orthogonal to d %.2f mm\n",
              life.to_mm(m.displacement.max), life.to_mm(m.along_d.rms), life.to_mm(m.orthogonal.rms));
  std::printf(
      "  Gaussian-curvature sign reversals (+ to -, - to +) %.2f%% of %zu vertices; %zu went flat, %zu left "
      "flat (flat: |K| L^2 <= %g, L = %.3g m, the model's diagonal)\n",
      100.0 * m.sign_reversal_fraction, m.curvature_vertices, m.into_flat, m.out_of_flat, o.dead_band,
      life.to_mm(m.reference_length) / 1000.0);
  if (!m.reversals_by_band.empty())
    std::printf("  reversals where clearly curved: %s\n",
                describe_band_reversals(m.reversals_by_band, life.to_mm(1.0) / 1000.0).c_str());
  for (const std::string& warning : r.warnings) std::printf("  warning: %s\n", warning.c_str());
  if (!record.attached.empty()) {
    long moved = 0, vertices = 0;
    double largest = 0.0;
    for (const AttachedPartRecord& part : record.attached) {
      moved += part.max_displacement > 0.0;
      vertices += part.vertex_count;
      largest = std::max(largest, part.max_displacement);
    }
    std::printf("  attached parts: %zu within %.1f mm of the region (%ld vertices); %ld moved with the surface, up to "
                "%.2f mm\n",
                record.attached.size(), life.to_mm(record.attach_reach), vertices, moved, life.to_mm(largest));
  }
  std::printf("  wrote %s and %s\n", o.out.c_str(), o.metrics.c_str());
}

}  // namespace

void add_deform_command(CLI::App& root) {
  auto o = std::make_shared<DeformCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "deform",
      "One push/pull on a model: move the handle by --displacement, deform the region with --method,\n"
      "write the deformed model (--out) and the evaluation numbers (--metrics).");
  cmd->add_option("MESH", o->mesh, "Model to deform (.gltf, .glb, .drc, .off, .obj, .ply)")->required();
  cmd->add_option(
      "--handle", o->handle_file,
      "File of 0-based handle vertex indices (white-space separated): an OFF/OBJ/PLY's own vertex "
      "numbers, a glTF's, GLB's or Draco file's welded surface's (as `pushpull info` counts them)");
  cmd->add_option(
         "--handle-at", o->handle_at,
         "Handle = vertices within --handle-radius, measured along the surface, of the surface point "
         "closest to this one (model frame, metres at life size)")
      ->expected(3)
      ->check(finite_number());
  cmd->add_option("--handle-radius", o->handle_radius, "Radius for --handle-at (metres at life size)")
      ->check(finite_above(0.0));
  cmd->add_option("--fixed", o->fixed_file,
                  "File of 0-based fixed vertex indices, numbered as --handle's (the region stops there)");
  cmd->add_option("--roi-radius", o->roi_radius,
                  "Region = vertices within this geodesic (edge-path) distance of the handle (metres at life "
                  "size); its border is fixed")
      ->check(finite_above(0.0, false));
  cmd->add_option("--displacement", o->displacement,
                  "Push/pull displacement d of the handle (metres at life size)")
      ->expected(3)
      ->required()
      ->check(finite_number());
  cmd->add_option("--method", o->method,
                  "arap-s, arap-sr, arap-m, arap-n, sr-arap, arap-h, arap-sr-h or asan")
      ->capture_default_str()
      ->check(method_name());
  cmd->add_option("--mu", o->mu, "asan: stretch factor of the region along d_o (> 1)")
      ->capture_default_str()
      ->check(finite_above(1.0));
  cmd->add_option("--stretch-direction", o->stretch_direction, "asan: direction d_o (default: d)")
      ->expected(3)
      ->check(finite_number());
  cmd->add_option("--asan-base", o->asan_base, "asan: membrane energy, arap-sr or arap-m")
      ->check(asan_base_name())
      ->capture_default_str();
  cmd->add_option("--alpha", o->alpha, "sr-arap: rotation smoothness weight")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--lambda", o->lambda,
                  "arap-h, arap-sr-h: bending weight against the membrane (0: arap-m; relative to the mean "
                  "vertex area; the paper's lambda runs the other way)")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--rings", o->rings,
                  "arap-n: neighbourhood size n (1: the one-ring with its rims, arap-sr)")
      ->capture_default_str()
      ->check(whole_number_in(1, 1000));
  CLI::Option* iterations = cmd->add_option("--iterations", o->iterations, "Maximum local-global iterations")
                                ->capture_default_str()
                                ->check(whole_number_in(0, std::numeric_limits<int>::max()));
  CLI::Option* tolerance =
      cmd->add_option(
             "--tolerance", o->tolerance,
             "Accuracy: stop when the estimated largest vertex distance to the exact minimiser is below "
             "T |d| (1e-2: 1 mm on a 100 mm pull); 0 = run exactly --iterations")
          ->capture_default_str()
          ->check(finite_above(0.0, false));
  CLI::Option* energy_tolerance =
      cmd->add_option(
             "--energy-tolerance", o->energy_tolerance,
             "Also stop when the relative energy change |E_k - E_k-1| / E_k-1 is below this (default: " +
                 tolerance_text(deform::DeformOptions{}.energy_tolerance) + "; 0 = off)")
          ->check(finite_above(0.0, false));
  CLI::Option* anderson = cmd->add_option("--anderson", o->anderson,
                                          "Anderson acceleration window, 0 = plain local-global iterations "
                                          "(default: " +
                                              std::to_string(deform::DeformOptions{}.anderson_window) + ")")
                              ->check(whole_number_in(0, 100));
  // The paper's setting is its own count and rule: an option that would change them is refused with it.
  CLI::Option* paper =
      cmd->add_flag(
             "--paper-iterations", o->paper_iterations,
             "The paper's setting: 50 plain local-global iterations, no acceleration, no stopping rule "
             "(as in the paper, not converged; the error estimate is still reported; not with --iterations, "
             "--tolerance, --energy-tolerance, --anderson or the starts' --smooth-start-min-free and "
             "--coarse-start-min-free: it starts from rest)")
          ->excludes(iterations)
          ->excludes(tolerance)
          ->excludes(energy_tolerance)
          ->excludes(anderson);
  CLI::Option* smooth_start =
      cmd->add_option(
             "--smooth-start-min-free", o->smooth_start_min_free,
             "asan: regions with at least this many free vertices start from the handle's move spread "
             "biharmonically (the same minimiser in fewer iterations on large regions); -1 = always from "
             "rest "
             "(default: " +
                 std::to_string(deform::DeformOptions{}.smooth_start_min_free) + ")")
          ->check(whole_number_in(-1, std::numeric_limits<int>::max()));
  CLI::Option* coarse_start =
      cmd->add_option("--coarse-start-min-free", o->coarse_start_min_free,
                      "asan: regions with at least this many free vertices are solved first on a coarser "
                      "tessellation of the region, and the iterations start from that shape (the same "
                      "minimiser in fewer iterations on large regions); -1 = never (default: " +
                          std::to_string(deform::DeformOptions{}.coarse_start_min_free) + ")")
          ->check(whole_number_in(-1, std::numeric_limits<int>::max()));
  paper->excludes(smooth_start)->excludes(coarse_start);
  cmd->add_option("--sections", o->sections, "Number of section planes (perpendicular to d) in the metrics")
      ->capture_default_str()
      ->check(whole_number_in(0, 1000));
  cmd->add_flag("!--no-attached-parts", o->attached_parts,
               "Leave separate parts (lamps, plates, trims) where they are instead of letting the ones near the "
               "region follow the deformed surface");
  cmd->add_option(
         "--attach-reach", o->attach_reach,
         "Parts within this distance of the region follow the surface (metres at life size; default: "
         "3% of the region's bounding-box diagonal)")
      ->check(finite_above(0.0, false));
  cmd->add_option(
         "--weld-tolerance", o->weld_tolerance,
         "Weld the file's patches within this distance, relative to the bounding-box diagonal (as "
         "`pushpull info --weld-tolerance`; a glTF's index files number the vertices of this weld, an "
         "OFF/OBJ/PLY's the file's own)")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--dead-band", o->dead_band,
                  "Curvature sign: |K| L^2 <= this counts as flat (zero) in sign statistics, L = the model's "
                  "bounding-box diagonal (the rule `render --color curvature-sign` draws)")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  add_life_size_options(*cmd, o->life_size);
  cmd->add_option("--out", o->out,
                  "Deformed model to write (.glb, .off, .obj, .ply; in the input's file units)")
      ->required();
  cmd->add_option("--metrics", o->metrics, "METRICS.json to write")->required();
  cmd->callback([o] { run_deform(*o); });
}

}  // namespace pushpull::app
