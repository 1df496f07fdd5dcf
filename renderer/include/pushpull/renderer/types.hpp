// Renderer-side input types. The renderer knows no file format: app/ converts models into these.
//
// Frames: positions are in the mesh frame; a draw places a mesh in the world (the review stage or
// the model frame) with T_world_mesh, which must be a rotation, translation and uniform scale
// (normals are transformed by its upper 3x3). Views: View::view maps world to eye (T_eye_world,
// right-handed, camera looks down -Z), View::projection maps eye to Vulkan clip space (y down,
// depth 0..1); see camera.hpp for helpers. Units: whatever the model uses (glTF: metres).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace pushpull::renderer {

// An RGBA8 image, rows top to bottom, 4 bytes per pixel. srgb: the bytes are sRGB-encoded colour
// (base colour, legends) rather than linear data (metallic-roughness, normal maps).
struct TextureRGBA8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> pixels;  // width * height * 4
  bool srgb = true;
};

// glTF 2.0 metallic-roughness material (+ KHR_materials_clearcoat factors). Texture fields hold
// TextureIds from Renderer::add_texture; -1 means none. Colours are linear. All textures use TEXCOORD_0.
struct Material {
  // Default: a warm modelling clay (sRGB ~ #C39560), unlike the cool grey background even in shadow.
  glm::vec4 base_colour{0.55f, 0.30f, 0.12f, 1.0f};
  float metallic = 0.0f;
  float roughness = 0.35f;
  float normal_scale = 1.0f;
  float clearcoat = 0.0f;  // 0..1 strength of a clear varnish layer (car paint)
  float clearcoat_roughness = 0.03f;
  glm::vec3 emissive{0.0f};
  int base_colour_texture = -1;         // sRGB
  int metallic_roughness_texture = -1;  // linear, G = roughness, B = metallic
  int normal_texture = -1;              // linear, tangent space, +Y up in UV space (glTF)
  int occlusion_texture = -1;           // linear, R = ambient occlusion
  float occlusion_strength = 1.0f;
  int emissive_texture = -1;  // sRGB, multiplied by emissive
  bool double_sided = true;   // informational: every surface is drawn double-sided (open CAD shells)
  bool unlit = false;         // flat colour, no lighting (arrow heads, debug)
};

// Per-vertex review overlay weights (0 or 1; interpolated across faces so class boundaries fall at
// mid-edges). A vertex may be in several (a handle vertex is also in the ROI). Drawn: ROI tinted, fixed blue,
// handle red; fixed and handle both set marks a hover highlight (magenta, outside every colour map).
struct OverlayWeights {
  float roi = 0.0f;
  float fixed = 0.0f;
  float handle = 0.0f;
};

// One indexed triangle mesh, split into submeshes that share vertices but not materials.
// Shapes: positions, normals #V*3 floats (x,y,z per vertex); uvs #V*2 or empty; scalars #V or empty
// (the value the colour maps show: displacement magnitude, Gaussian curvature...); overlays #V or
// empty; indices #T*3, counter-clockwise seen from the front. Empty normals are computed.
struct RenderMesh {
  struct Submesh {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    int material = -1;  // index into Scene::materials; -1 = default grey
  };
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<float> uvs;
  std::vector<float> scalars;
  std::vector<OverlayWeights> overlays;
  std::vector<uint32_t> indices;
  std::vector<Submesh> submeshes;  // empty = one submesh over all indices with material -1

  [[nodiscard]] uint32_t vertex_count() const { return static_cast<uint32_t>(positions.size() / 3); }
};

// A view: one eye, or the single mono camera.
struct View {
  glm::mat4 view{1.0f};        // T_eye_world
  glm::mat4 projection{1.0f};  // eye -> Vulkan clip space
};

// What the fragments show.
enum class ColorMode : uint32_t {
  material = 0,        // glTF materials under the studio lighting
  displacement = 1,    // RenderMesh::scalars / scalar_max through the displacement colour map
  curvature_sign = 2,  // sign of RenderMesh::scalars: yellow > +eps, blue < -eps, grey otherwise
};

// Per-frame shading settings.
struct FrameSettings {
  ColorMode color_mode = ColorMode::material;
  float scalar_max = 1.0f;         // displacement that maps to the top of the colour map (> 0)
  float curvature_epsilon = 0.0f;  // |K| <= eps counts as zero (grey)
  bool show_overlays = true;       // handle red, fixed blue, ROI tinted
  glm::vec3 up{0.0f, 1.0f, 0.0f};  // world up for the studio environment (glTF: +Y)
  glm::vec4 clear_colour{0.16f, 0.17f, 0.19f, 1.0f};  // linear
  float exposure = 1.0f;
  bool lighting = true;  // false: flat colours (exact colour-map values; tests, colour pickers)
  bool show_legend = true;  // draw the legend set by Renderer::set_legend (a window: yes; the headset's eyes: no)
};

}  // namespace pushpull::renderer
