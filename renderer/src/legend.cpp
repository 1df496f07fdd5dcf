// Legends rasterised on the CPU (text from stb_easy_font's quads) and drawn by the renderer as a
// screen-space overlay, so they appear in the XR eyes and the mirror as well as in PNGs.
#include "easy_font.hpp"
#include "pushpull/renderer/colormap.hpp"
#include "pushpull/renderer/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace pushpull::renderer {
namespace {

struct Canvas {
  TextureRGBA8 image;
  Canvas(uint32_t w, uint32_t h, glm::vec4 background) {
    image.width = w;
    image.height = h;
    image.pixels.resize(size_t(w) * h * 4);
    for (size_t i = 0; i < size_t(w) * h; ++i) set_index(i, background);
  }
  void set_index(size_t i, glm::vec4 c) {
    // RGB are linear: encode to sRGB; alpha stays linear.
    image.pixels[4 * i + 0] = static_cast<uint8_t>(std::lround(255.0f * linear_to_srgb(c.r)));
    image.pixels[4 * i + 1] = static_cast<uint8_t>(std::lround(255.0f * linear_to_srgb(c.g)));
    image.pixels[4 * i + 2] = static_cast<uint8_t>(std::lround(255.0f * linear_to_srgb(c.b)));
    image.pixels[4 * i + 3] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(c.a, 0.0f, 1.0f)));
  }
  void fill(int x0, int y0, int x1, int y1, glm::vec4 c) {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, int(image.width));
    y1 = std::min(y1, int(image.height));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set_index(size_t(y) * image.width + size_t(x), c);
  }
  // Text with its top-left corner at (x, y); `scale` pixels per font unit (the font is ~7 units high).
  void text(float x, float y, const char* s, float scale, glm::vec4 c) {
    std::vector<char> quads(16 * 4 * 256);
    unsigned char colour[4] = {255, 255, 255, 255};
    std::vector<char> copy(s, s + std::char_traits<char>::length(s) + 1);
    const int n = stb_easy_font_print(0.0f, 0.0f, copy.data(), colour, quads.data(), int(quads.size()));
    detail::lengthen_bars(copy.data(), 0.0f, quads.data(), n);
    for (int q = 0; q < n; ++q) {
      const float* v0 = reinterpret_cast<const float*>(quads.data() + (q * 4 + 0) * 16);
      const float* v2 = reinterpret_cast<const float*>(quads.data() + (q * 4 + 2) * 16);
      fill(int(std::lround(x + v0[0] * scale)), int(std::lround(y + v0[1] * scale)),
           int(std::lround(x + v2[0] * scale)), int(std::lround(y + v2[1] * scale)), c);
    }
  }
  static float text_width(const char* s, float scale) {
    std::vector<char> copy(s, s + std::char_traits<char>::length(s) + 1);
    return float(stb_easy_font_width(copy.data())) * scale;
  }
};

const glm::vec4 kPanel{0.02f, 0.02f, 0.025f, 0.78f};
const glm::vec4 kText{0.95f, 0.95f, 0.95f, 1.0f};

}  // namespace

std::vector<double> round_ticks(double max_value) {
  if (!(max_value > 0.0) || !std::isfinite(max_value)) return {};
  // The smallest round step that gives at most five intervals below max_value.
  const double magnitude = std::pow(10.0, std::floor(std::log10(max_value / 5.0)));
  double step = 10.0 * magnitude;
  for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (max_value / (m * magnitude) <= 5.0 + 1e-9) {
      step = m * magnitude;
      break;
    }
  std::vector<double> ticks;
  for (int k = 0; k * step <= max_value * (1.0 + 1e-9); ++k) ticks.push_back(k * step);
  return ticks;
}

TextureRGBA8 make_displacement_legend(float max_value, const std::string& title, uint32_t width,
                                      uint32_t height) {
  Canvas canvas(width, height, kPanel);
  const float scale = std::max(1.0f, std::floor(float(height) / 110.0f));
  const float line = 10.0f * scale;
  // Title: as large as the tick labels when it fits, smaller when not, wrapped at spaces as a last resort.
  const float room = float(width) - line * 1.2f;
  float title_scale = scale;
  while (title_scale > 1.0f && Canvas::text_width(title.c_str(), title_scale) > room) title_scale -= 1.0f;
  std::vector<std::string> title_lines{title};
  if (Canvas::text_width(title.c_str(), title_scale) > room) {
    title_lines.clear();
    std::string current, word;
    for (std::size_t i = 0; i <= title.size(); ++i) {
      if (i < title.size() && title[i] != ' ') {
        word += title[i];
        continue;
      }
      const std::string joined = current.empty() ? word : current + " " + word;
      if (!current.empty() && Canvas::text_width(joined.c_str(), title_scale) > room) {
        title_lines.push_back(current);
        current = word;
      } else {
        current = joined;
      }
      word.clear();
    }
    if (!current.empty()) title_lines.push_back(current);
  }
  const float title_line = 10.0f * title_scale;
  for (std::size_t i = 0; i < title_lines.size(); ++i)
    canvas.text(line * 0.6f, line * 0.5f + title_line * float(i), title_lines[i].c_str(), title_scale, kText);
  const int bar_x0 = int(line * 0.8f), bar_x1 = bar_x0 + int(line * 1.6f);
  const int bar_y0 = int(line * 0.5f + title_line * float(title_lines.size()) + line * 0.7f);
  const int bar_y1 = int(height) - int(line * 1.0f);
  for (int y = bar_y0; y < bar_y1; ++y) {
    const float t = 1.0f - float(y - bar_y0) / float(std::max(1, bar_y1 - bar_y0 - 1));
    canvas.fill(bar_x0, y, bar_x1, y + 1, glm::vec4(displacement_colour(t), 1.0f));
  }
  for (const double value : round_ticks(double(max_value))) {
    const double t = value / double(max_value);
    const int y = bar_y1 - 1 - int(std::lround(t * double(bar_y1 - bar_y0 - 1)));
    canvas.fill(bar_x1, y - int(scale / 2), bar_x1 + int(line * 0.5f), y - int(scale / 2) + int(scale),
                kText);
    char label[32];
    std::snprintf(label, sizeof(label), "%g", value);
    canvas.text(float(bar_x1) + line * 0.8f, float(y) - 3.5f * scale, label, scale, kText);
  }
  return canvas.image;
}

TextureRGBA8 make_curvature_legend(uint32_t width, uint32_t height) {
  return make_sign_legend(width, height,
                          // flat: |K| L^2 within the sign rule's band; edge: a vertex on the mesh boundary
                          // or a non-manifold edge, not measured (a CAD user read the grey seams as flat)
                          {"K > 0", "K < 0", "flat, edge"});
}

TextureRGBA8 make_sign_legend(uint32_t width, uint32_t height, const std::array<std::string, 3>& labels) {
  Canvas canvas(width, height, kPanel);
  // Three rows of a swatch and its label fill the panel: 0.6 line margins above and below, rows 1.5 lines
  // apart (5.2 lines in all); the text as large as a row holds, at least the font's own size.
  const float line = std::max(10.0f, float(height) / 5.2f);
  const float scale = std::max(1.0f, std::floor(line / 10.0f));
  const glm::vec3 colours[3] = {curvature_sign_colour(1.0f, 0.0f), curvature_sign_colour(-1.0f, 0.0f),
                                curvature_sign_colour(0.0f, 0.0f)};
  for (int i = 0; i < 3; ++i) {
    const float y = line * (0.6f + 1.5f * float(i));
    canvas.fill(int(line * 0.6f), int(y), int(line * 1.8f), int(y + line), glm::vec4(colours[i], 1.0f));
    canvas.text(line * 2.4f, y + 0.5f * (line - 7.0f * scale), labels[size_t(i)].c_str(), scale, kText);
  }
  return canvas.image;
}

LegendLayout legend_layout(uint32_t view_width, uint32_t view_height) {
  const float width = float(std::max(view_width, 1u)), height = float(std::max(view_height, 1u));
  const float h = 0.32f, w = h * height / width * 0.55f;
  LegendLayout layout;
  layout.rect = {0.015f, 1.0f - h - 0.015f, 0.015f + w, 0.985f};
  layout.curvature_rect = {0.015f, 0.985f - 0.5f * h, 0.015f + kSignLegendWiden * w, 0.985f};
  layout.height_px = std::max(110u, uint32_t(height * h));
  layout.width_px = std::max(60u, uint32_t(float(layout.height_px) * 0.55f));
  layout.curvature_width_px = uint32_t(kSignLegendWiden * float(layout.width_px));
  return layout;
}

}  // namespace pushpull::renderer
