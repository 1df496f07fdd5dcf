#include "life_size.hpp"

#include "commands.hpp"
#include "number_checks.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace pushpull::app {
namespace {

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void add_life_size_options(CLI::App& command, LifeSizeOptions& options) {
  command
      .add_option("--scale", options.scale,
                  "Life-size factor: metres per file unit (default 1: the file is in metres, as glTF is). "
                  "Points, radii and distances on the command line are life-size metres")
      ->check(finite_above(0.0));
  command
      .add_option("--length", options.length_m,
                  "Life size: scale so the longest side of the model is this many metres (overrides --scale)")
      ->check(finite_above(0.0));
}

LifeSize::LifeSize(const LifeSizeOptions& options, const Eigen::AlignedBox3d& bounds,
                   const std::string& model) {
  scale_ = options.scale;
  if (options.length_m) {
    const double longest = bounds.isEmpty() ? 0.0 : bounds.sizes().maxCoeff();
    if (!(longest > 0.0) || !std::isfinite(longest))
      throw CommandError(model + ": the model has zero size; cannot scale it to --length " +
                         format_number(*options.length_m) + " m");
    scale_ = *options.length_m / longest;
  }
  if (!(scale_ > 0.0) || !std::isfinite(scale_))
    throw CommandError(options.length_m ? "--length " + format_number(*options.length_m) + " gives " + model +
                                              " no finite positive scale"
                                        : std::string("--scale must be a finite number > 0"));
}

std::vector<double> LifeSize::to_file_units(const std::vector<double>& metres) const {
  std::vector<double> out;
  out.reserve(metres.size());
  for (double value : metres) out.push_back(value / scale_);
  return out;
}

Eigen::AlignedBox3d bounds_of(const Eigen::MatrixXd& V) {
  Eigen::AlignedBox3d box;
  for (Eigen::Index v = 0; v < V.rows(); ++v) box.extend(V.row(v).transpose());
  return box;
}

std::optional<std::string> size_hint(double longest_m) {
  if (!std::isfinite(longest_m) || !(longest_m > 0.0) || (longest_m >= 0.3 && longest_m <= 30.0))
    return std::nullopt;
  char text[256];
  // A car or a part of one in millimetres or centimetres, read as metres: the units, not the size, are off
  // (450 "m" may be either: both are said).
  std::string units;
  for (const auto& [factor, name] : {std::pair{0.001, "millimetres"}, std::pair{0.01, "centimetres"}}) {
    if (longest_m * factor >= 0.3 && longest_m * factor <= 30.0) {
      std::snprintf(text, sizeof text, "%sif the file is in %s, --scale %g makes it %.3g m long",
                    units.empty() ? "" : "; ", name, factor, longest_m * factor);
      units += text;
    }
  }
  if (!units.empty()) {
    std::snprintf(text, sizeof text, "its longest side is %.4g m: ", longest_m);
    return text + units + " (--length M makes it M metres long)";
  }
  std::snprintf(
      text, sizeof text,
      "its longest side is %.3g m; --length M makes it M metres long (a car: --length 4.2), --scale S "
      "sets metres per file unit",
      longest_m);
  return std::string(text);
}

}  // namespace pushpull::app
