// What `pushpull review` says of a plain mesh file's up axis. OFF, OBJ and PLY name none (glTF's is +Y), so
// the review takes +Y, the default of --up; a model that then stands on its thin side (a bonnet modelled
// Z-up: 1.20 m tall and 0.11 m deep) is said, with the option that lays it flat.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>

namespace pushpull::app {

// The note for a model of `path` whose bounding box measures `size_m` (x, y, z; metres at the review's
// scale) with +Y taken as up: nullopt for a file that is not OFF, OBJ or PLY (glTF's up is +Y), or where +Y
// is its thinnest side or within 1.2x of it (a car modelled
// Y-up, a cube), else a sentence naming the file, the height and the thin side it stands on, and the --up
// that lays it flat. Pure.
std::optional<std::string> plain_mesh_up_note(const std::string& path, const Eigen::Vector3d& size_m);

}  // namespace pushpull::app
