// Life size on the command line: `--scale S` / `--length M`, shared by info, deform and render.
//
// Convention (one for every command): a model's coordinates stay in its file units everywhere, in the
// solver, the renderer and every written file. The life-size factor `scale` maps file units to metres
// (metres = file units * scale; 1 unless --scale or --length is given, i.e. files are taken to be in
// metres, as glTF is). What the user types on the command line (points, radii, displacements, camera
// positions, eye distance) is in metres at life size and is divided by the scale to reach file units;
// lengths the commands print are file units times the scale, in millimetres.
// Thread-safety: plain values and pure functions.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace pushpull::app {

struct LifeSizeOptions {
  double scale = 1.0;              // --scale: file units to metres
  std::optional<double> length_m;  // --length: the longest side of the bounding box at life size, metres
};

// Registers --scale and --length on `command` (both positive; --length takes precedence).
void add_life_size_options(CLI::App& command, LifeSizeOptions& options);

// The factor from file units to metres at life size.
class LifeSize {
 public:
  LifeSize() = default;
  // From the options and the model's bounding box in file units. Throws CommandError naming `model`
  // when --length is given for a model of zero size.
  LifeSize(const LifeSizeOptions& options, const Eigen::AlignedBox3d& bounds, const std::string& model);

  [[nodiscard]] double scale() const { return scale_; }
  // A length or point typed in life-size metres, in file units.
  [[nodiscard]] double to_file_units(double metres) const { return metres / scale_; }
  [[nodiscard]] Eigen::Vector3d to_file_units(const Eigen::Vector3d& metres) const { return metres / scale_; }
  // Every entry of an option's values (e.g. X Y Z) divided by the scale; an empty list stays empty.
  [[nodiscard]] std::vector<double> to_file_units(const std::vector<double>& metres) const;
  // A length in file units, in life-size millimetres (for printing).
  [[nodiscard]] double to_mm(double file_units) const { return file_units * scale_ * 1000.0; }

 private:
  double scale_ = 1.0;
};

// What to say of a model whose longest side is `longest_m` metres at the scale taken, outside 0.3 .. 30 m (a
// walk-around size): a CAD export in millimetres (300 .. 30,000 "m") or centimetres is named with the --scale
// that makes it life size, any other size with --length ("a car: --length 4.2"); nullopt inside the range.
[[nodiscard]] std::optional<std::string> size_hint(double longest_m);

// The bounding box of #V by 3 positions (empty box for no rows).
Eigen::AlignedBox3d bounds_of(const Eigen::MatrixXd& V);

}  // namespace pushpull::app
