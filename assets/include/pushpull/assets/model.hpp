// pushpull::assets::load_model: the one entry point that loads any supported model file.
//
// Formats: .gltf and .glb (glTF 2.0, tinygltf, with KHR_draco_mesh_compression and
// KHR_mesh_quantization), raw Draco .drc, and .off/.obj/.ply through deform's mesh reader.
// The result has two sides:
//  - the render side (scene.hpp): primitives with their attributes in node-local frames and their
//    T_model_node, materials, textures, samplers and images as in the file;
//  - the deform side: one welded triangle surface (deform_mesh, model frame) and, per primitive,
//    the map from render vertex to deform vertex (Primitive::deform_vertex).
// A deformation computed on deform_mesh.V goes back to every render vertex through that map
// (write_glb in write.hpp does that).
//
// Units and frames: model frame = world coordinates of the file after all node transforms, in the
// file's units (glTF: metres). No scale is applied to any stored coordinate: `scale` is the factor
// that brings the model to life size (1 unless LoadOptions asks otherwise); a viewer applies it in
// T_stage_model, a command line converts life-size lengths with it. Points on the command line
// (--handle-at) are model-frame points, i.e. before the scale.
//
// Untrusted input: URIs must stay inside the model's folder (no absolute paths, no '..' escaping
// it, no scheme other than data:); sizes, counts and indices are checked against the data and
// against Limits before anything is allocated for them. A refused file throws AssetError naming
// the file and the problem; recoverable problems (a missing image, an unsupported extension)
// become warnings in the report.
//
// Ownership: Model is a value type (movable, copyable). Thread-safety: load_model is reentrant;
// a Model is safe to read from several threads; share it as std::shared_ptr<const Model>.
#pragma once

#include "pushpull/assets/error.hpp"
#include "pushpull/assets/scene.hpp"
#include "pushpull/assets/weld.hpp"

#include <pushpull/deform/mesh.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pushpull::assets {

// Hard limits for untrusted input. Anything beyond them is refused before allocation.
struct Limits {
  std::uint64_t max_file_bytes = std::uint64_t{1} << 31;  // model file and each external file
  std::uint64_t max_vertices = 50'000'000;                // summed over all primitive instances
  std::uint64_t max_triangles = 50'000'000;
  std::uint64_t max_instances = 1'000'000;  // primitive instances after flattening
  int max_json_depth = 64;                  // nesting of the glTF JSON
  int max_node_depth = 256;                 // node hierarchy depth
};

struct LoadOptions {
  WeldOptions weld;
  Limits limits;
  // Life size: either an explicit factor, or a target length in metres for the longest side of the
  // bounding box (takes precedence when set). Neither changes stored coordinates: see Model::scale.
  double scale = 1.0;
  std::optional<double> target_length_m;
  // A glTF that requires an extension the loader does not support and that may change the geometry is
  // refused (glTF 2.0); false loads it anyway with a warning saying so (`pushpull info`, which reports it).
  bool refuse_unsupported_required = true;
};

struct LoadReport {
  std::string format;                        // "glTF", "GLB", "Draco", "OFF", ...
  std::vector<std::string> warnings;         // each names what and where
  std::vector<std::string> extensions_used;  // from extensionsUsed
  std::vector<std::string> extensions_required;
  std::vector<std::string> unsupported_extensions;  // used but not interpreted by the loader
  WeldStats weld;
};

// Opaque: the parsed source document, kept so that write_glb can carry nodes, materials and
// extensions through unchanged. Null for formats without a scene (.drc, .off, ...).
struct SourceDocument;

struct Model {
  std::filesystem::path source_path;
  // Every file the load read: the model file (load_model) and each external file its URIs named (glTF
  // buffers and images), as the paths opened. Commands refuse outputs that would replace one of them.
  std::vector<std::filesystem::path> source_files;
  std::vector<Primitive> primitives;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Sampler> samplers;
  std::vector<Image> images;

  deform::Mesh deform_mesh;    // welded surface, model frame, file units
  Eigen::AlignedBox3d bounds;  // of deform_mesh.V, model frame
  double scale = 1.0;          // life-size factor (dimensionless), see the header comment
  LoadReport report;

  std::shared_ptr<const SourceDocument> source;  // immutable, shared between copies
};

// Loads `path` (format chosen by the extension, case-insensitive). Throws AssetError.
Model load_model(const std::filesystem::path& path, const LoadOptions& options = {});

// Same, from bytes in memory (for tests and fuzzing). `name` picks the format by its extension
// and names the input in messages; external URIs resolve against `base_dir` (empty: refused).
Model load_model_from_memory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                             const std::filesystem::path& base_dir, const LoadOptions& options = {});

// A Model around a bare triangle mesh (e.g. from deform's OFF/OBJ/PLY reader) without welding:
// one primitive, deform_mesh == mesh, render vertex i = deform vertex i, no materials. Lets a mesh
// be written as GLB or drawn by the renderer. `name` names the primitive and the source.
Model model_from_mesh(const deform::Mesh& mesh, const std::string& name = "mesh");

// Whether load_model can read this path's extension.
bool is_supported_model_path(const std::filesystem::path& path);

// The load's warnings (model.report.warnings), each naming the file: "<source_path>: " put before those that
// do not start with it already (some name a mesh or primitive after it, some only the problem). For commands
// that print them beside their own.
[[nodiscard]] std::vector<std::string> warnings_naming_the_file(const Model& model);

}  // namespace pushpull::assets
