// CPU geometry for the renderer: vertex normals, and overlay meshes (the p0 -> p1 arrow, section
// curves as tubes) and legends. Thread-safety: pure functions.
#pragma once

#include "pushpull/renderer/types.hpp"

#include <glm/glm.hpp>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace pushpull::renderer {

// Area-weighted vertex normals. positions #V*3, indices #T*3; returns #V*3 unit normals (zero-area
// neighbourhoods get +Z). Cost O(#V + #T): about 1 ms for 110K triangles on one core.
std::vector<float> compute_vertex_normals(std::span<const float> positions,
                                          std::span<const uint32_t> indices);
void compute_vertex_normals(std::span<const float> positions, std::span<const uint32_t> indices,
                            std::span<float> normals_out);

// An arrow from p0 to p1 (shaft radius `radius`, head twice as wide and 4 radii long), as a mesh
// with one submesh of material `material`.
// Generalised winding number of a triangle mesh at `point` (Jacobson et al. 2013: the signed solid angle
// of every triangle seen from the point, summed, over 4 pi): about +-1 inside a closed surface, 0
// outside, in between near holes of an open one. positions #V*3, indices #T*3 (counter-clockwise seen
// from outside: inside is +1). O(#T).
double winding_number(std::span<const float> positions, std::span<const uint32_t> indices,
                      const glm::vec3& point);

RenderMesh make_arrow(const glm::vec3& p0, const glm::vec3& p1, float radius, int material);

// Tubes of radius `radius` along polylines (each polyline: points in order; closed if the first
// and last point coincide), one submesh of material `material`.
RenderMesh make_tubes(const std::vector<std::vector<glm::vec3>>& polylines, float radius, int material);

// Round tick values for a scale from 0 to max_value: 0 and multiples of a step of 1, 2, 2.5 or 5 times a
// power of ten, at most max_value, 3 to 6 of them (102 -> 0 25 50 75 100). Empty when max_value <= 0
// or is not finite.
std::vector<double> round_ticks(double max_value);

// A legend for the displacement colour map: a vertical bar from 0 (bottom) to max_value (top), ticks
// at round_ticks(max_value) placed at their value, and a title such as "|d| mm" (stb_easy_font, ASCII)
// that is made smaller, then wrapped at spaces, to fit the width (never clipped while a word fits).
// Sized width x height pixels, sRGB, on a translucent dark panel.
TextureRGBA8 make_displacement_legend(float max_value, const std::string& title, uint32_t width,
                                      uint32_t height);

// A legend for the curvature sign: yellow "K > 0", blue "K < 0", grey "K = 0".
TextureRGBA8 make_curvature_legend(uint32_t width, uint32_t height);
// The same three swatches (yellow, blue, grey) with other labels (at most 12 characters each), e.g. where the
// sign reversed: "to K > 0", "to K < 0", "kept". Text that does not fit the width is cut at the panel's edge.
TextureRGBA8 make_sign_legend(uint32_t width, uint32_t height, const std::array<std::string, 3>& labels);

// Where the legends go in a view of view_width x view_height pixels (Renderer::set_legend rectangles, 0..1, y
// down): the lower-left corner, the displacement legend about a third of the view high (`rect`, a texture of
// width_px x height_px), the curvature legend half as high (`curvature_rect`, width_px x height_px / 2).
// Where the legends go in a view (rect: x0, y0, x1, y1 in 0..1 of the view) and their texture sizes: the
// displacement legend `rect` (width_px x height_px), the sign legends `curvature_rect`, half as high and
// kSignLegendWiden times as wide (curvature_width_px x height_px / 2: their labels are longer).
inline constexpr float kSignLegendWiden = 1.6f;
struct LegendLayout {
  glm::vec4 rect{0.0f};
  glm::vec4 curvature_rect{0.0f};
  uint32_t width_px = 0;
  uint32_t height_px = 0;
  uint32_t curvature_width_px = 0;
};
LegendLayout legend_layout(uint32_t view_width, uint32_t view_height);

}  // namespace pushpull::renderer
