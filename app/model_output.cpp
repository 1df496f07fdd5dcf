#include "model_output.hpp"

#include "commands.hpp"

#include "pushpull/assets/write.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace pushpull::app {
namespace {

// The message once with the path in front (the libraries' messages may start with it already).
std::string naming(const std::filesystem::path& path, const std::string& what) {
  return what.rfind(path.string(), 0) == 0 ? what : path.string() + ": " + what;
}

}  // namespace

bool is_glb_path(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

std::vector<std::string> write_deformed_model(const std::filesystem::path& path,
                                              const std::filesystem::path& source,
                                              const deform::Mesh& rest_mesh, const assets::Model* scene,
                                              const Eigen::MatrixXd& V) {
  if (is_glb_path(path)) {
    try {
      if (scene) return assets::write_glb(*scene, V, path);
      return assets::write_glb(assets::model_from_mesh(rest_mesh, path.stem().string()), V, path);
    } catch (const std::exception& e) {
      throw CommandError(naming(path, e.what()));
    }
  }
  std::vector<std::string> warnings;
  try {
    // The source file's vertices: the model's own where it was read as it is, or, where assets welded
    // them, each vertex of the file moved by its weld's displacement: vertices the weld merged keep their own
    // positions (they were near, not equal). For a copy of the file (same format), one whose weld did not
    // move, or that no triangle uses, keeps its text (a row of NaN); written as triangles (another format,
    // or a layout the copy refuses), the file's own vertices and triangles in its numbering, so that the
    // vertex numbers of an index file still name the same points in the output.
    Eigen::MatrixXd source_positions = V;
    deform::Mesh triangles{V, rest_mesh.F};
    if (scene && scene->primitives.size() == 1 && deform::mesh_format_from_path(source) &&
        deform::mesh_format_from_path(path)) {
      const std::vector<int>& weld = scene->primitives.front().deform_vertex;
      // The file as it is now must be the one the model was read from (same vertex count and triangles):
      // one changed or gone since is not used, and the output is the welded surface, said in a warning.
      deform::Mesh file;
      std::string unusable;
      try {
        file = deform::read_mesh(source);
      } catch (const std::exception& e) {
        unusable = e.what();
      }
      const std::vector<std::uint32_t>& indices = scene->primitives.front().indices;
      bool same = unusable.empty() && file.V.rows() == static_cast<Eigen::Index>(weld.size()) &&
                  static_cast<std::size_t>(file.F.size()) == indices.size();
      for (Eigen::Index f = 0; same && f < file.F.rows(); ++f)
        for (int c = 0; c < 3 && same; ++c)
          same = static_cast<std::uint32_t>(file.F(f, c)) == indices[static_cast<std::size_t>(3 * f + c)];
      if (!same)
        warnings.push_back(
            path.string() + ": written as the welded surface (" + std::to_string(V.rows()) +
            " vertices): " + source.string() +
            (unusable.empty() ? " changed since it was read" : " can no longer be read: " + unusable));
      else {
        source_positions.setConstant(file.V.rows(), 3, std::nan(""));
        triangles = file;
        for (std::size_t v = 0; v < weld.size(); ++v) {
          const int w = weld[v];
          if (w < 0 || w >= V.rows() || V.row(w) == rest_mesh.V.row(w)) continue;
          const auto row = static_cast<Eigen::Index>(v);
          triangles.V.row(row) = file.V.row(row) + (V.row(w) - rest_mesh.V.row(w));
          source_positions.row(row) = triangles.V.row(row);
        }
      }
    }
    for (const std::string& note : deform::write_deformed_mesh(path, source, source_positions, triangles))
      warnings.push_back(path.string() + ": " + note);
  } catch (const std::exception& e) {
    throw CommandError(naming(path, e.what()));
  }
  // A glTF scene written as a bare mesh keeps the welded surface only: said, not silently dropped.
  if (scene && !deform::mesh_format_from_path(source)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s holds the welded surface only (%ld vertices, %ld triangles): the glTF's %zu "
                  "primitive(s), %zu material(s) and texture coordinates are not in it (an output ending in "
                  ".glb keeps them)",
                  path.string().c_str(), static_cast<long>(V.rows()), static_cast<long>(rest_mesh.F.rows()),
                  scene->primitives.size(), scene->materials.size());
    warnings.emplace_back(text);
  }
  return warnings;
}

}  // namespace pushpull::app
