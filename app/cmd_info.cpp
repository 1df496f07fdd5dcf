// pushpull info MODEL: what is in a model (size, counts, components, materials, extensions, weld).
#include "commands.hpp"

#include <pushpull/assets/info.hpp>
#include <pushpull/assets/model.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace pushpull::app {

namespace {

struct InfoArguments {
  std::string model;
  double scale = 1.0;
  std::optional<double> length_m;
  double weld_tolerance = pushpull::assets::WeldOptions{}.relative_tolerance;
};

void run_info(const InfoArguments& arguments) {
  pushpull::assets::LoadOptions options;
  options.scale = arguments.scale;
  options.target_length_m = arguments.length_m;
  options.weld.relative_tolerance = arguments.weld_tolerance;
  try {
    const pushpull::assets::Model model = pushpull::assets::load_model(arguments.model, options);
    std::fputs(pushpull::assets::describe_model(model).c_str(), stdout);
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
  info->add_option("--scale", arguments->scale,
                   "Life-size factor applied to the model (file units to metres)")
      ->check(CLI::PositiveNumber);
  info->add_option("--length", arguments->length_m,
                   "Life size: scale so the longest side is this many metres")
      ->check(CLI::PositiveNumber);
  info->add_option("--weld-tolerance", arguments->weld_tolerance,
                   "Weld tolerance relative to the bounding-box diagonal")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  info->callback([arguments] { run_info(*arguments); });
}

}  // namespace pushpull::app
