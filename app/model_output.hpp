// Writing a deformed model where the user asked, for deform, review and replay alike: a .glb as a scene, an
// OFF/OBJ/PLY as a copy of a source file of that format with only its positions replaced, else as triangles.
// Thread-safety: none needed (plain functions; concurrent calls on different paths are safe).
#pragma once

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace pushpull::app {

// Whether `path` names a GLB (extension .glb, any case).
[[nodiscard]] bool is_glb_path(const std::filesystem::path& path);

// Writes V (#V by 3, the deformed positions of rest_mesh, file units) to `path`, atomically:
// - .glb: `scene` (the model as loaded, nodes and materials kept; assets::write_glb), or rest_mesh as one
//   plain mesh where there is no scene;
// - .off, .obj, .ply: where `source` (the file the model was read from) has that format, a copy of it
//   with the positions replaced (deform::write_deformed_mesh: polygons, attributes and comments kept; each
//   file vertex moved by its weld's displacement where assets welded them); else, for a model read from an
//   OFF/OBJ/PLY, that file's own vertices (moved the same way) and triangles in its numbering, so that
//   vertex numbers (index files) keep naming the same points; else rest_mesh's triangles with V.
// Returns warnings for the user, each naming `path`: what the output cannot carry (a glTF scene written as a
// bare mesh), input attributes kept that no longer match the surface (normals), a layout written as triangles
// instead. Throws CommandError naming the file and the problem.
[[nodiscard]] std::vector<std::string> write_deformed_model(const std::filesystem::path& path,
                                                            const std::filesystem::path& source,
                                                            const deform::Mesh& rest_mesh,
                                                            const assets::Model* scene,
                                                            const Eigen::MatrixXd& V);

}  // namespace pushpull::app
