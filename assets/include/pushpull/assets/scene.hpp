// pushpull::assets render-side scene: what a renderer needs to draw a loaded model.
//
// Units: the model file's units (glTF: metres). Frames: every Primitive stores its vertex data in
// its node's local frame, as in the file; T_model_node maps node-local coordinates to the model
// (world) frame, i.e. after all node transforms, before any life-size scale (Model::scale).
// Shapes: row-major Eigen matrices, one vertex per row, ready to upload as tightly packed arrays.
// Ownership: plain value types. Thread-safety: none of their own; share as shared_ptr<const ...>.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace pushpull::assets {

template <int Cols>
using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Cols, Eigen::RowMajor>;

// A reference to a texture from a material slot (glTF textureInfo).
struct TextureRef {
  int texture = -1;    // index into Model::textures, -1 = none
  int texcoord = 0;    // which TEXCOORD_n set the slot samples
  float scale = 1.0f;  // normalTexture.scale or occlusionTexture.strength; 1 elsewhere
  [[nodiscard]] bool present() const { return texture >= 0; }
};

enum class AlphaMode { opaque, mask, blend };

// glTF metallic-roughness material (core properties interpreted; extensions named, not interpreted,
// and carried through unchanged to a written GLB).
struct Material {
  std::string name;
  Eigen::Vector4f base_color_factor{1.0f, 1.0f, 1.0f, 1.0f};  // linear RGBA
  TextureRef base_color_texture;                              // sRGB RGBA
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  TextureRef metallic_roughness_texture;  // B = metallic, G = roughness
  TextureRef normal_texture;              // tangent space; scale = normal scale
  TextureRef occlusion_texture;           // R channel; scale = strength
  Eigen::Vector3f emissive_factor{0.0f, 0.0f, 0.0f};
  TextureRef emissive_texture;  // sRGB
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  std::vector<std::string> extensions;  // e.g. KHR_materials_clearcoat (not interpreted)
};

// glTF sampler; the numeric values are the OpenGL enums glTF uses (-1 = unspecified).
struct Sampler {
  int mag_filter = -1;
  int min_filter = -1;
  int wrap_s = 10497;  // REPEAT
  int wrap_t = 10497;
};

struct Texture {
  std::string name;
  int image = -1;    // index into Model::images, -1 = none (e.g. only an extension source)
  int sampler = -1;  // index into Model::samplers, -1 = default sampler
};

// An image as stored in the file (PNG/JPEG/...), not decoded: decode with stb_image or similar.
struct Image {
  std::string name;
  std::string mime_type;              // "image/png", "image/jpeg", ... or empty when unknown
  std::vector<std::uint8_t> encoded;  // the file bytes; empty when the image was missing
  int width = 0;                      // from the image header, 0 when unknown
  int height = 0;
  bool missing = false;  // referenced but unreadable (a warning was reported)
};

// One drawn glTF primitive instance: node `node` draws primitive `primitive` of mesh `mesh`.
// An instanced mesh (used by several nodes) gives one Primitive per node.
// Only triangles are kept (strips and fans become lists; points and lines are skipped with a warning).
struct Primitive {
  std::string name;   // "<node name>/<mesh name>#<primitive>"
  int node = -1;      // glTF node index (-1 for files without nodes, e.g. .drc; a plain mesh, OFF/OBJ/PLY,
                      // holds its positions relative to its bounding-box centre, the centre in T_model_node)
  int mesh = -1;      // glTF mesh index
  int primitive = 0;  // index of the primitive in that mesh
  int material = -1;  // index into Model::materials, -1 = glTF default material
  Eigen::Matrix4d T_model_node = Eigen::Matrix4d::Identity();  // node-local -> model frame

  RowMatrixXf<3> positions;               // #v by 3, node-local frame
  RowMatrixXf<3> normals;                 // #v by 3 as read (glTF: unit length, not renormalized;
                                          // zero or non-finite ones become +Z), or 0 rows when absent
  RowMatrixXf<4> tangents;                // #v by 4 (xyz unit, w = +-1), or 0 rows
  std::vector<RowMatrixXf<2>> texcoords;  // TEXCOORD_0.. each #v by 2
  RowMatrixXf<4> colors;                  // COLOR_0 as linear RGBA, or 0 rows
  std::vector<std::uint32_t> indices;     // triangle list, 3 per triangle, each < #v

  // #v entries: the row of Model::deform_mesh.V this render vertex was welded into, or -1 when the
  // vertex is used by no triangle. Render vertices split at UV or normal seams share a deform vertex.
  std::vector<int> deform_vertex;

  [[nodiscard]] Eigen::Index vertex_count() const { return positions.rows(); }
  [[nodiscard]] std::size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace pushpull::assets
