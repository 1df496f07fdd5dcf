// pushpull::assets::write_glb: writes a (deformed) model as a GLB that changes only what moved.
//
// The written file has the source's nodes (names, transforms, hierarchy), materials, textures,
// samplers and images, and every primitive's attributes.
// Vertices: a render vertex whose deform vertex moved (row of `deformed_V` not exactly equal to the
// same row of model.deform_mesh.V) gets its position from `deformed_V` through
// Primitive::deform_vertex (rendered back into its node's local frame), and its normal/tangent
// rotated with the local surface rotation, so hard edges and UV seams survive. Every other vertex
// keeps the position, normal and tangent read from the file, bit for bit (float accessors; quantized
// or Draco-compressed attributes are written as the floats they decode to). With WriteOptions::draco
// every attribute is quantized again, so nothing is bit-identical then.
// Images: as they were read (see src/image_carry.hpp): data: URIs and, when the file is written into
// the folder the source's URIs resolve against, external URIs stay as they were; written elsewhere,
// external images are embedded with their bytes unchanged; a missing image stays referenced by its
// URI, with a warning. Nothing is replaced by a placeholder.
// A mesh instanced by several nodes is written once per node (the instances deform differently).
// Skins, animations and morph targets are not written (a warning says so). Coordinates stay in the
// file's units: Model::scale is not applied.
//
// The write is atomic: the bytes go to a temporary file beside `path`, are flushed, then renamed
// over `path`; a failure leaves any previous file at `path` untouched.
// Thread-safety: reentrant. Throws AssetError naming the file and the problem.
#pragma once

#include "pushpull/assets/model.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace pushpull::assets {

struct WriteOptions {
  bool draco = false;            // re-compress meshes with KHR_draco_mesh_compression
  int draco_position_bits = 14;  // quantization when draco is set
  int draco_normal_bits = 10;
  int draco_texcoord_bits = 12;
  int draco_speed = 5;  // 0 = best compression .. 10 = fastest
  // The folder the written file will sit in, for image URIs (see above). write_glb sets it from its
  // path when empty; for encode_glb, empty means "unknown": present external images are embedded.
  std::filesystem::path output_dir;
};

// deformed_V: #deform vertices by 3 in the model frame (same rows as model.deform_mesh.V);
// pass model.deform_mesh.V to write the model unchanged. Returns warnings about dropped content.
std::vector<std::string> write_glb(const Model& model, const Eigen::MatrixXd& deformed_V,
                                   const std::filesystem::path& path, const WriteOptions& options = {});

// The GLB bytes write_glb would write (for tests and in-memory use).
std::vector<std::uint8_t> encode_glb(const Model& model, const Eigen::MatrixXd& deformed_V,
                                     const WriteOptions& options, std::vector<std::string>* warnings);

}  // namespace pushpull::assets
