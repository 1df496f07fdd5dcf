#include "world_label.hpp"

#include "pushpull/renderer/text_label.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace pushpull::app {

WorldLabel::WorldLabel(renderer::Renderer& renderer, float line_height, unsigned max_quads)
    : renderer_(renderer), line_height_(line_height), max_quads_(max_quads) {
  renderer::Material panel, highlight, glyph;
  panel.unlit = highlight.unlit = glyph.unlit = true;
  panel.base_colour = {0.015f, 0.017f, 0.022f, 1.0f};
  highlight.base_colour = {0.05f, 0.25f, 0.60f, 1.0f};
  glyph.base_colour = {0.95f, 0.95f, 0.92f, 1.0f};
  const auto p = int(renderer_.add_material(panel)), h = int(renderer_.add_material(highlight)),
             g = int(renderer_.add_material(glyph));
  mesh_ = renderer_.add_mesh(renderer::make_text_label_mesh(max_quads_, p, h, g), /*streamed=*/true);
}

void WorldLabel::set_text(const std::vector<std::string>& lines, int highlight_line) {
  visible_ = true;
  if (has_text_ && lines == lines_ && highlight_line == highlight_) return;
  lines_ = lines;
  highlight_ = highlight_line;
  has_text_ = true;
  const renderer::TextLabelLayout layout =
      renderer::layout_text_label(lines_, line_height_, max_quads_, highlight_line);
  height_ = layout.height;
  renderer_.update_vertices(mesh_, layout.positions);
}

void WorldLabel::place(const Eigen::Vector3d& anchor, const Eigen::Vector3d& viewer, double scale) {
  // Facing the viewer, upright as far as that allows (x stays horizontal).
  Eigen::Vector3d z = viewer - anchor;
  if (z.norm() < 1e-6) z = Eigen::Vector3d::UnitZ();
  z.normalize();
  Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z);
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitX();  // looked at from straight above or below
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  glm::mat4 T(1.0f);
  for (int r = 0; r < 3; ++r) {
    T[0][r] = float(scale * x[r]);
    T[1][r] = float(scale * y[r]);
    T[2][r] = float(scale * z[r]);
    T[3][r] = float(anchor[r]);
  }
  T_stage_label_ = T;
}

std::optional<renderer::Draw> WorldLabel::draw() const {
  if (!visible_ || !has_text_) return std::nullopt;
  renderer::Draw d;
  d.mesh = mesh_;
  d.T_world_mesh = T_stage_label_;
  d.colour_mapped = false;
  d.on_top = true;
  return d;
}

}  // namespace pushpull::app
