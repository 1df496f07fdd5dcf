// `pushpull render`: a PNG of a model or of a deformation result, with material shading or the
// review colour maps (displacement magnitude, sign of Gaussian curvature) and overlays.
#include "commands.hpp"
#include "life_size.hpp"
#include "messages_off_stdout.hpp"
#include "number_checks.hpp"
#include "output_guard.hpp"
#include "render_inputs.hpp"
#include "render_model.hpp"
#include "render_session.hpp"
#include "up_axis_note.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/file_output.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

assets::Model load(const std::string& path, const char* what, double weld_tolerance) {
  if (!fs::exists(path)) throw CommandError(path + ": " + what + " file does not exist");
  try {
    assets::LoadOptions options;
    options.weld.relative_tolerance = weld_tolerance;
    return assets::load_model(path, options);
  } catch (const std::exception& e) {
    throw CommandError(e.what());
  }
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
  (void)messages_off_stdout({options.out});
  if (options.up.size() == 3 && options.up[0] == 0.0 && options.up[1] == 0.0 && options.up[2] == 0.0)
    throw UsageError("--up: the up direction must not be zero");
  if (options.color == "curvature-reversal" && options.deformed.empty())
    throw UsageError(
        "--color curvature-reversal needs --deformed: it shows where the sign reversed from MODEL "
        "to the deformed shape");
  if (const std::string problem = deform::output_path_problem(options.out); !problem.empty())
    throw CommandError((options.out.empty() ? std::string("--out") : options.out) + ": " + problem);
  // The picture is PNG whatever the name says: a name that promises another format (x.jpg) is refused
  // rather than written as a PNG under it. A name without an extension (/dev/stdout) is taken as it is.
  {
    std::string extension = fs::path(options.out).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (!extension.empty() && extension != ".png")
      throw CommandError(options.out + ": render writes PNG pictures; give --out a name ending in .png");
  }
  const assets::Model model = load(options.model, "model", options.weld_tolerance);
  const LifeSize life(options.life_size, model.bounds, options.model);
  if (!options.up_given)
    if (const auto note = plain_mesh_up_note(options.model, model.bounds.sizes() * life.scale()))
      std::fprintf(stderr, "pushpull render: note: %s\n", note->c_str());
  convert_to_file_units(options, life);
  auto render = std::make_shared<const RenderModel>(build_render_model(model));
  for (const std::string& w : assets::warnings_naming_the_file(model))
    std::fprintf(stderr, "pushpull render: warning: %s\n", w.c_str());
  for (const auto& w : render->warnings) std::fprintf(stderr, "pushpull render: warning: %s\n", w.c_str());
  if (render->mesh.indices.empty())
    throw CommandError(options.model + ": the model has no triangles to draw");

  const Eigen::MatrixXd& V0 = model.deform_mesh.V;
  std::optional<assets::Model> result;
  if (!options.deformed.empty()) {
    result = load(options.deformed, "deformed result", options.weld_tolerance);
    if (result->deform_mesh.V.rows() != V0.rows())
      throw CommandError(options.deformed + ": has " + std::to_string(result->deform_mesh.V.rows()) +
                         " (welded) vertices but " + options.model + " has " + std::to_string(V0.rows()) +
                         ": not a deformation of that model");
  }
  {
    std::vector<InputFile> inputs = model_inputs(model.source_files);
    if (result)
      for (const fs::path& file : result->source_files)
        inputs.push_back({file, "the deformed result's files"});
    for (const auto& [file, role] :
         {std::pair{&options.handle_file, "the --handle file"},
          std::pair{&options.fixed_file, "the --fixed file"}, std::pair{&options.roi_file, "the --roi file"}})
      if (!file->empty()) inputs.push_back({*file, role});
    refuse_output_over_inputs("--out", options.out, inputs);
  }
  const Eigen::MatrixXd& V = result ? result->deform_mesh.V : V0;
  render_to_png(prepare_render_inputs(std::move(render), model.deform_mesh, V, result.has_value(), options,
                                      life.scale(), &model),
                options);
}

}  // namespace

void add_render_command(CLI::App& root) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "render",
      "Render a model or a deformation result to PNG (Vulkan; headless on Mesa lavapipe when there is no "
      "GPU).\n"
      "Colour maps follow Le Vaou et al. 2020, Fig. 12: displacement magnitude (left) and the sign of the\n"
      "Gaussian curvature, yellow positive, blue negative (right). Handle red (magenta on the displacement "
      "map, whose top is red), fixed blue, ROI tinted green.");
  cmd->add_option("model", options->model, "Model file: .gltf .glb .drc .off .obj .ply")->required();
  cmd->add_option(
      "--deformed", options->deformed,
      "Deformation result of MODEL (same welded vertices): anything `pushpull deform` reads or writes");
  cmd->add_option("--out", options->out, "Output PNG")->required();
  cmd->add_option("--size", options->size, "Image width and height in pixels (per eye with --stereo)")
      ->expected(2)
      ->check(whole_number_in(1, 16384));
  cmd->add_option(
         "--color", options->color,
         "What the colours show (curvature-reversal: where the sign of the Gaussian curvature reversed "
         "from MODEL to --deformed, in its new sign's colour)")
      ->check(CLI::IsMember({"material", "displacement", "curvature-sign", "curvature-reversal"}));
  cmd->add_option(
         "--camera", options->camera,
         "Orbit camera: AZIMUTH ELEVATION [ZOOM] (degrees around --up, azimuth 0 looking from +Z, or from -Y "
         "when --up is along Z, turning towards --up x that axis; ZOOM > 1 moves closer). Default 35 20 1 "
         "frames the whole model")
      ->expected(2, 3)
      ->check(finite_number())
      ->type_name("AZIMUTH ELEVATION [ZOOM]");
  cmd->add_option("--eye", options->eye,
                  "Camera position X Y Z (model frame, metres at life size); overrides --camera")
      ->expected(3)
      ->check(finite_number());
  cmd->add_option("--target", options->target,
                  "Point looked at X Y Z (model frame, metres at life size; default: the model's centre)")
      ->expected(3)
      ->check(finite_number());
  CLI::Option* up = cmd->add_option("--up", options->up, "World up X Y Z (default 0 1 0, glTF)")
                        ->expected(3)
                        ->check(finite_number());
  cmd->add_option("--fov", options->fov_deg, "Vertical field of view, degrees")->check(finite_in(1.0, 170.0));
  cmd->add_option(
         "--scalar-max", options->scalar_max,
         "Displacement shown as the top of the colour map (metres at life size; default: the largest; "
         "the paper's Fig. 1 and the replay report use |d|, the same colour for the same move in "
         "every method)")
      ->check(finite_above(0.0));
  cmd->add_option(
         "--weld-tolerance", options->weld_tolerance,
         "Weld the file's patches within this distance, relative to the bounding-box diagonal (as "
         "`pushpull info --weld-tolerance`; a glTF's --handle/--fixed files number the vertices of this "
         "weld, an OFF/OBJ/PLY's the file's own)")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--dead-band", options->dead_band,
                  "Curvature sign: |K| L^2 <= dead-band counts as flat (grey), L = MODEL's bounding-box "
                  "diagonal (the rule of deform's metrics); faces of flat panels are drawn flat")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--handle", options->handle_file,
                  "Handle vertices (index file, numbered as `pushpull deform --handle` reads it), drawn red");
  cmd->add_option("--fixed", options->fixed_file, "Fixed vertices (index file), drawn blue");
  cmd->add_option("--roi", options->roi_file, "Region-of-interest vertices (index file), tinted");
  cmd->add_option("--handle-at", options->handle_at,
                  "Handle = vertices near X Y Z (model frame, metres at life size)")
      ->expected(3)
      ->check(finite_number());
  cmd->add_option("--handle-radius", options->handle_radius, "Radius for --handle-at (metres at life size)")
      ->check(finite_above(0.0));
  cmd->add_option("--arrow", options->arrow,
                  "Draw the push/pull arrow p0 -> p1: X0 Y0 Z0 X1 Y1 Z1 (model frame, metres at life size)")
      ->expected(6)
      ->check(finite_number());
  cmd->add_option("--sections", options->sections,
                  "Draw N section curves of the (deformed) surface, planes orthogonal to the --arrow "
                  "direction spread evenly over the deformed model's extent along it (`pushpull deform "
                  "--sections` spreads its planes over the region before the pull instead: METRICS.json "
                  "sections[].offset)")
      ->check(whole_number_in(0, 1000));
  add_life_size_options(*cmd, options->life_size);
  cmd->add_flag("--no-legend", options->no_legend, "Leave out the colour-map legend");
  cmd->add_flag("--flat", options->flat, "Colour maps without lighting (exact colours)");
  cmd->add_option("--stereo", options->ipd,
                  "Render two eyes IPD apart (metres at life size, e.g. 0.064) in one frame; the PNG holds "
                  "left | right")
      ->check(finite_above(0.0));
  cmd->add_option("--samples", options->samples, "MSAA samples")->check(CLI::IsMember({1, 2, 4, 8}));
  cmd->add_flag("--validation", options->validation,
                "Enable VK_LAYER_KHRONOS_validation; fail on any message");
  cmd->add_option("--benchmark", options->benchmark_frames,
                  "Also time N frames, then N frames each uploading full deformed positions + normals");
  cmd->callback([options, up] {
    options->up_given = up->count() > 0;
    run_render(*options);
  });
}

}  // namespace pushpull::app
