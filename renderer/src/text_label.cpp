#include "pushpull/renderer/text_label.hpp"

#include "easy_font.hpp"

#include <algorithm>

namespace pushpull::renderer {
namespace {

constexpr uint32_t kPanelVertices = 8;  // panel quad + highlight quad
constexpr float kFontLineHeight = 12.0f;  // stb_easy_font's line advance in its pixels
constexpr float kPadding = 4.0f;          // around the text, font pixels

// stb_easy_font's vertex: x, y, z, RGBA8.
struct FontVertex {
  float x, y, z;
  unsigned char colour[4];
};

void set_quad(std::vector<float>& p, uint32_t first_vertex, float x0, float y0, float x1, float y1, float z) {
  const float corners[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  for (uint32_t k = 0; k < 4; ++k) {
    p[3 * (first_vertex + k) + 0] = corners[k][0];
    p[3 * (first_vertex + k) + 1] = corners[k][1];
    p[3 * (first_vertex + k) + 2] = z;
  }
}

}  // namespace

RenderMesh make_text_label_mesh(uint32_t max_quads, int panel_material, int highlight_material,
                                int glyph_material) {
  RenderMesh mesh;
  const uint32_t quads = 2 + max_quads;
  mesh.positions.assign(size_t(quads) * 12, 0.0f);
  mesh.normals.resize(size_t(quads) * 12);
  for (size_t v = 0; v < size_t(quads) * 4; ++v) {
    mesh.normals[3 * v + 0] = 0.0f;
    mesh.normals[3 * v + 1] = 0.0f;
    mesh.normals[3 * v + 2] = 1.0f;
  }
  mesh.indices.reserve(size_t(quads) * 6);
  for (uint32_t q = 0; q < quads; ++q) {
    const uint32_t v = 4 * q;
    for (uint32_t i : {v, v + 1, v + 2, v, v + 2, v + 3}) mesh.indices.push_back(i);
  }
  mesh.submeshes = {{0, 6, panel_material}, {6, 6, highlight_material}, {12, 6 * max_quads, glyph_material}};
  return mesh;
}

TextLabelLayout layout_text_label(std::span<const std::string> lines, float line_height, uint32_t max_quads,
                                  int highlight_line) {
  TextLabelLayout out;
  out.positions.assign(size_t(2 + max_quads) * 12, 0.0f);
  // Lay the text out in font pixels (y down from the top-left), then map to the label frame.
  std::vector<FontVertex> glyphs;
  std::vector<FontVertex> buffer(4 * 1024);
  float text_width = 0.0f;
  for (size_t l = 0; l < lines.size(); ++l) {
    std::string text = lines[l];
    for (char& c : text)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    text_width = std::max(text_width, float(stb_easy_font_width(text.data())));
    const int n = stb_easy_font_print(0.0f, float(l) * kFontLineHeight, text.data(), nullptr, buffer.data(),
                                      int(buffer.size() * sizeof(FontVertex)));
    detail::lengthen_bars(text.data(), float(l) * kFontLineHeight, buffer.data(), n, int(sizeof(FontVertex)));
    glyphs.insert(glyphs.end(), buffer.begin(), buffer.begin() + 4 * n);
  }
  const float scale = line_height / kFontLineHeight;
  const float width_px = text_width + 2.0f * kPadding;
  const float height_px = float(lines.size()) * kFontLineHeight + 2.0f * kPadding - 3.0f;
  out.width = width_px * scale;
  out.height = height_px * scale;
  // Font pixel (x, y) -> label (x, y): centred in x, the panel's bottom at y = 0.
  auto map_x = [&](float x) { return (x + kPadding - 0.5f * width_px) * scale; };
  auto map_y = [&](float y) { return (height_px - (y + kPadding)) * scale; };
  const float z_text = 0.002f * line_height, z_bar = 0.001f * line_height;
  set_quad(out.positions, 0, -0.5f * out.width, 0.0f, 0.5f * out.width, out.height, 0.0f);
  if (highlight_line >= 0 && size_t(highlight_line) < lines.size()) {
    const float top = float(highlight_line) * kFontLineHeight - 2.0f;
    set_quad(out.positions, 4, -0.5f * out.width + 0.5f * kPadding * scale, map_y(top + kFontLineHeight),
             0.5f * out.width - 0.5f * kPadding * scale, map_y(top), z_bar);
  }
  const size_t quads = glyphs.size() / 4;
  out.quads = uint32_t(std::min<size_t>(quads, max_quads));
  out.truncated = quads > max_quads;
  for (uint32_t q = 0; q < out.quads; ++q) {
    const FontVertex* g = &glyphs[4 * size_t(q)];
    for (uint32_t k = 0; k < 4; ++k) {
      const uint32_t v = kPanelVertices + 4 * q + k;
      out.positions[3 * v + 0] = map_x(g[k].x);
      out.positions[3 * v + 1] = map_y(g[k].y);
      out.positions[3 * v + 2] = z_text;
    }
  }
  return out;
}

}  // namespace pushpull::renderer
