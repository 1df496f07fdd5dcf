// pushpull info MODEL: what is in a model (size, counts, components, materials, extensions, weld).
#include "commands.hpp"
#include "life_size.hpp"
#include "number_checks.hpp"
#include "up_axis_note.hpp"

#include <pushpull/assets/info.hpp>
#include <pushpull/assets/model.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace pushpull::app {

namespace {

struct InfoArguments {
  std::string model;
  LifeSizeOptions life_size;
  double weld_tolerance = pushpull::assets::WeldOptions{}.relative_tolerance;
};

void run_info(const InfoArguments& arguments) {
  pushpull::assets::LoadOptions options;
  options.scale = arguments.life_size.scale;
  options.target_length_m = arguments.life_size.length_m;
  options.weld.relative_tolerance = arguments.weld_tolerance;
  options.refuse_unsupported_required = false;  // info names such an extension (the other commands refuse)
  try {
    const pushpull::assets::Model model = pushpull::assets::load_model(arguments.model, options);
    std::fputs(pushpull::assets::describe_model(model).c_str(), stdout);
    // What the review would say before a session: other units than metres, a plain mesh on its side.
    const Eigen::Vector3d size_m = model.bounds.sizes() * model.scale;
    if (const auto hint = size_hint(size_m.maxCoeff())) std::printf("note:         %s\n", hint->c_str());
    if (const auto note = plain_mesh_up_note(arguments.model, size_m))
      std::printf("note:         %s (render and review take --up)\n", note->c_str());
  } catch (const pushpull::assets::AssetError& e) {
    throw CommandError(e.what());
  }
}

}  // namespace

void add_info_command(CLI::App& root) {
  auto arguments = std::make_shared<InfoArguments>();
  CLI::App* info = root.add_subcommand(
      "info",
      "Print what is in a model: size, counts, components, materials, extensions and what welding did");
  info->add_option("model", arguments->model, "Model file (.gltf, .glb, .drc, .off, .obj, .ply)")->required();
  add_life_size_options(*info, arguments->life_size);
  info->add_option("--weld-tolerance", arguments->weld_tolerance,
                   "Weld tolerance relative to the bounding-box diagonal")
      ->check(finite_above(0.0, false))
      ->capture_default_str();
  info->callback([arguments] { run_info(*arguments); });
}

}  // namespace pushpull::app
