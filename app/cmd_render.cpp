// `pushpull render`: a PNG of a model or of a deformation result, with material shading or the
// review colour maps (displacement magnitude, sign of Gaussian curvature) and overlays.
#include "commands.hpp"
#include "life_size.hpp"
#include "render_model.hpp"
#include "render_session.hpp"
#include "vertex_selection.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/deform/surface_point.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

assets::Model load(const std::string& path, const char* what) {
  if (!fs::exists(path)) throw CommandError(path + ": " + what + " file does not exist");
  try {
    return assets::load_model(path);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
}

Eigen::Vector3d vec3(const std::vector<double>& v, size_t offset = 0) {
  return {v[offset], v[offset + 1], v[offset + 2]};
}

// The lengths typed on the command line (life-size metres) in the model's file units.
void convert_to_file_units(RenderCommandOptions& o, const LifeSize& life) {
  o.eye = life.to_file_units(o.eye);
  o.target = life.to_file_units(o.target);
  o.handle_at = life.to_file_units(o.handle_at);
  o.handle_radius = life.to_file_units(o.handle_radius);
  o.arrow = life.to_file_units(o.arrow);
  if (o.scalar_max) o.scalar_max = life.to_file_units(*o.scalar_max);
  if (o.ipd) o.ipd = life.to_file_units(*o.ipd);
}

void run_render(RenderCommandOptions options) {
  const assets::Model model = load(options.model, "model");
  const LifeSize life(options.life_size, model.bounds, options.model);
  convert_to_file_units(options, life);
  RenderInputs inputs;
  inputs.render = build_render_model(model);
  for (const auto& w : inputs.render.warnings)
    std::fprintf(stderr, "pushpull render: warning: %s\n", w.c_str());
  if (inputs.render.mesh.indices.empty())
    throw CommandError(options.model + ": the model has no triangles to draw");
  inputs.life_size_scale = life.scale();

  const Eigen::MatrixXd& V0 = model.deform_mesh.V;
  const Eigen::MatrixXi& F = model.deform_mesh.F;
  Eigen::MatrixXd V = V0;
  if (!options.deformed.empty()) {
    const assets::Model result = load(options.deformed, "deformed result");
    if (result.deform_mesh.V.rows() != V0.rows())
      throw CommandError(options.deformed + ": has " + std::to_string(result.deform_mesh.V.rows()) +
                         " (welded) vertices but " + options.model + " has " + std::to_string(V0.rows()) +
                         ": not a deformation of that model");
    V = result.deform_mesh.V;
    inputs.deformed = true;
  }
  inputs.positions = render_positions(inputs.render, V);
  inputs.normals =
      inputs.deformed ? deformed_normals(inputs.render, inputs.positions) : inputs.render.file_normals;

  // Colour-map values, deform side -> render vertices.
  if (options.color == "displacement") {
    const Eigen::VectorXd magnitude = (V - V0).rowwise().norm();
    inputs.scalars = to_render_vertices(inputs.render, magnitude);
    inputs.scalar_max = magnitude.size() > 0 ? magnitude.maxCoeff() : 0.0;
  } else if (options.color == "curvature-sign") {
    // deform's one sign rule: flat when |K| L^2 <= dead-band, L = the model's bounding-box diagonal (the
    // same L and rule as `pushpull deform`'s metrics); flat panels drawn flat.
    const deform::GaussianCurvature after = deform::gaussian_curvature(V, F);
    const double threshold =
        deform::flat_curvature_threshold(deform::curvature_reference_length(V0), options.dead_band);
    std::vector<std::int8_t> signs = deform::curvature_signs(after, threshold);
    for (size_t i = 0; i < signs.size(); ++i)
      if (after.boundary[i]) signs[i] = 0;  // the boundary's turn is not surface curvature
    inputs.scalars = curvature_signs_on_render_vertices(inputs.render, V, signs);
  }

  // Overlays on deform vertices.
  const Eigen::Index nv = V0.rows();
  std::vector<renderer::OverlayWeights> deform_overlays(static_cast<size_t>(nv));
  bool any_overlay = false;
  auto mark = [&](const std::vector<int>& vertices, float renderer::OverlayWeights::*field) {
    for (int v : vertices) deform_overlays[size_t(v)].*field = 1.0f;
    any_overlay = any_overlay || !vertices.empty();
  };
  if (!options.roi_file.empty()) mark(read_index_file(options.roi_file, nv), &renderer::OverlayWeights::roi);
  if (!options.fixed_file.empty())
    mark(read_index_file(options.fixed_file, nv), &renderer::OverlayWeights::fixed);
  if (!options.handle_file.empty())
    mark(read_index_file(options.handle_file, nv), &renderer::OverlayWeights::handle);
  if (!options.handle_at.empty()) {
    if (options.handle_radius <= 0.0)
      throw CommandError("--handle-at needs --handle-radius > 0 (metres at life size)");
    // The same rule as `pushpull deform`: along the surface from the closest surface point.
    const deform::Mesh rest{V0, F};
    const deform::SurfacePoint hit = deform::closest_surface_point(rest, vec3(options.handle_at));
    mark(deform::surface_handle(rest, hit, options.handle_radius), &renderer::OverlayWeights::handle);
  }
  if (any_overlay) {
    inputs.overlays.resize(inputs.render.deform_vertex.size());
    for (size_t r = 0; r < inputs.overlays.size(); ++r) {
      const int d = inputs.render.deform_vertex[r];
      if (d >= 0) inputs.overlays[r] = deform_overlays[size_t(d)];
    }
  }
  if (!options.arrow.empty()) {
    inputs.arrow = std::make_pair(vec3(options.arrow, 0), vec3(options.arrow, 3));
    if (options.sections > 0) {
      const Eigen::Vector3d d = inputs.arrow->second - inputs.arrow->first;
      if (d.norm() <= 0.0) throw CommandError("--sections needs a non-zero --arrow direction");
      const Eigen::Vector3d dn = d.normalized();
      const Eigen::VectorXd along = V * dn;
      const double lo = along.minCoeff(), hi = along.maxCoeff();
      for (int k = 1; k <= options.sections; ++k) {
        const double offset = lo + (hi - lo) * double(k) / double(options.sections + 1);
        for (const auto& curve : deform::plane_section(V, F, dn * offset, dn)) {
          std::vector<glm::vec3> line;
          for (const auto& p : curve.points) line.emplace_back(float(p.x()), float(p.y()), float(p.z()));
          if (curve.closed && !line.empty()) line.push_back(line.front());
          inputs.sections.push_back(std::move(line));
        }
      }
    }
  } else if (options.sections > 0) {
    throw CommandError("--sections needs --arrow (the sections are orthogonal to the push/pull direction)");
  }
  render_to_png(inputs, options);
}

}  // namespace

void add_render_command(CLI::App& root) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "render",
      "Render a model or a deformation result to PNG (Vulkan; headless on Mesa lavapipe when there is no "
      "GPU).\n"
      "Colour maps follow Le Vaou et al. 2020, Fig. 12: displacement magnitude (left) and the sign of the\n"
      "Gaussian curvature, yellow positive, blue negative (right). Handle red, fixed blue, ROI tinted "
      "green.");
  cmd->add_option("model", options->model, "Model file: .gltf .glb .drc .off .obj .ply")->required();
  cmd->add_option(
      "--deformed", options->deformed,
      "Deformation result of MODEL (same welded vertices): anything `pushpull deform` reads or writes");
  cmd->add_option("--out", options->out, "Output PNG")->required();
  cmd->add_option("--size", options->size, "Image width and height in pixels (per eye with --stereo)")
      ->expected(2)
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--color", options->color, "What the colours show")
      ->check(CLI::IsMember({"material", "displacement", "curvature-sign"}));
  cmd->add_option(
         "--camera", options->camera,
         "Orbit camera: AZIMUTH ELEVATION [ZOOM] (degrees around --up from the model's front +Z towards "
         "+X; ZOOM > 1 moves closer). Default 35 20 1 frames the whole model")
      ->expected(2, 3);
  cmd->add_option("--eye", options->eye,
                  "Camera position X Y Z (model frame, metres at life size); overrides --camera")
      ->expected(3);
  cmd->add_option("--target", options->target,
                  "Point looked at X Y Z (model frame, metres at life size; default: the model's centre)")
      ->expected(3);
  cmd->add_option("--up", options->up, "World up X Y Z (default 0 1 0, glTF)")->expected(3);
  cmd->add_option("--fov", options->fov_deg, "Vertical field of view, degrees")
      ->check(CLI::Range(1.0, 170.0));
  cmd->add_option(
      "--scalar-max", options->scalar_max,
      "Displacement shown as the top of the colour map (metres at life size; default: the largest)");
  cmd->add_option("--dead-band", options->dead_band,
                  "Curvature sign: |K| L^2 <= dead-band counts as flat (grey), L = MODEL's bounding-box "
                  "diagonal (the rule of deform's metrics); faces of flat panels are drawn flat")
      ->capture_default_str();
  cmd->add_option("--handle", options->handle_file,
                  "Handle vertices (index file of deform vertices), drawn red");
  cmd->add_option("--fixed", options->fixed_file, "Fixed vertices (index file), drawn blue");
  cmd->add_option("--roi", options->roi_file, "Region-of-interest vertices (index file), tinted");
  cmd->add_option("--handle-at", options->handle_at,
                  "Handle = vertices near X Y Z (model frame, metres at life size)")
      ->expected(3);
  cmd->add_option("--handle-radius", options->handle_radius, "Radius for --handle-at (metres at life size)");
  cmd->add_option("--arrow", options->arrow,
                  "Draw the push/pull arrow p0 -> p1: X0 Y0 Z0 X1 Y1 Z1 (model frame, metres at life size)")
      ->expected(6);
  cmd->add_option(
      "--sections", options->sections,
      "Draw N section curves of the (deformed) surface, planes orthogonal to the --arrow direction");
  add_life_size_options(*cmd, options->life_size);
  cmd->add_flag("--no-legend", options->no_legend, "Leave out the colour-map legend");
  cmd->add_flag("--flat", options->flat, "Colour maps without lighting (exact colours)");
  cmd->add_option(
      "--stereo", options->ipd,
      "Render two eyes IPD apart (metres at life size, e.g. 0.064) in one frame; the PNG holds left | right");
  cmd->add_option("--samples", options->samples, "MSAA samples")->check(CLI::IsMember({1, 2, 4, 8}));
  cmd->add_flag("--validation", options->validation,
                "Enable VK_LAYER_KHRONOS_validation; fail on any message");
  cmd->add_option("--benchmark", options->benchmark_frames,
                  "Also time N frames, then N frames each uploading full deformed positions + normals");
  cmd->callback([options] { run_render(*options); });
}

}  // namespace pushpull::app
