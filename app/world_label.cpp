#include "world_label.hpp"

#include "pushpull/renderer/text_label.hpp"

#include <Eigen/Geometry>
#include <glm/matrix.hpp>

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
  width_ = layout.width;
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

void WorldLabel::place_on_image_plane(const Eigen::Vector3d& anchor, const Eigen::Vector3d& right,
                                      const Eigen::Vector3d& up, double scale) {
  const Eigen::Vector3d toward_viewer = right.cross(up);
  glm::mat4 T(1.0f);
  for (int r = 0; r < 3; ++r) {
    T[0][r] = float(scale * right[r]);
    T[1][r] = float(scale * up[r]);
    T[2][r] = float(scale * toward_viewer[r]);
    T[3][r] = float(anchor[r]);
  }
  T_stage_label_ = T;
}

void WorldLabel::place_top_left(const renderer::View& view, double line_fraction) {
  // The projection of renderer/camera.cpp: eye looking down -Z, +Y up; p[1][1] = -1 / tan(fov_y / 2),
  // p[0][0] = 1 / (aspect tan(fov_y / 2)), depth from p[2][2] = -f / (f - n) and p[3][2] = -f n / (f - n).
  const glm::mat4& p = view.projection;
  if (!(std::abs(p[1][1]) > 0.0f) || !(p[0][0] > 0.0f) || !(std::abs(p[2][2]) > 0.0f)) return;
  const double n = double(p[3][2]) / double(p[2][2]);
  const double f =
      std::abs(double(p[2][2]) + 1.0) > 1e-12 ? double(p[3][2]) / (double(p[2][2]) + 1.0) : 2.0 * n;
  if (!(n > 0.0) || !(f > n)) return;
  const double depth = n + 0.05 * (f - n);
  const double half_height = depth / std::abs(double(p[1][1])), half_width = depth / double(p[0][0]);
  const double scale = line_fraction * 2.0 * half_height / double(line_height_);
  const double margin = 0.5 * line_fraction * 2.0 * half_height;
  // The panel's bottom centre (its origin) in eye space, then to the world.
  const glm::vec4 anchor_eye(float(-half_width + margin + 0.5 * scale * double(width_)),
                             float(half_height - margin - scale * double(height_)), float(-depth), 1.0f);
  const glm::mat4 T_world_eye = glm::inverse(view.view);
  glm::mat4 T_eye_label{float(scale)};  // scale on the diagonal; the last column is the anchor
  T_eye_label[3] = anchor_eye;
  T_stage_label_ = T_world_eye * T_eye_label;
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
