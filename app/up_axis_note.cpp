#include "up_axis_note.hpp"

#include "pushpull/deform/mesh_io.hpp"

#include <cstdio>

namespace pushpull::app {

std::optional<std::string> plain_mesh_up_note(const std::string& path, const Eigen::Vector3d& size_m) {
  if (!deform::mesh_format_from_path(path) || !size_m.allFinite()) return std::nullopt;
  Eigen::Index thin = 0;
  const double thinnest = size_m.minCoeff(&thin);
  if (thin == 1 || !(size_m.y() > 1.2 * thinnest)) return std::nullopt;
  const char* axis = thin == 0 ? "X" : "Z";
  const char* up = thin == 0 ? "1 0 0" : "0 0 1";
  const char* down = thin == 0 ? "-1 0 0" : "0 0 -1";
  char text[512];
  std::snprintf(text, sizeof text,
                "%s names no up axis (OFF, OBJ and PLY have none): +Y is taken as up, which stands the model "
                "%.2f m tall on its %.2f m side; if it lies flat along %s, give --up %s (or %s) and --front "
                "towards its front",
                path.c_str(), size_m.y(), thinnest, axis, up, down);
  return std::string(text);
}

}  // namespace pushpull::app
