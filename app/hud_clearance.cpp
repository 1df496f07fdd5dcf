#include "hud_clearance.hpp"

#include <algorithm>
#include <array>

namespace pushpull::app {

std::optional<ImageRect> label_image_rect(const glm::mat4& T_world_label, float width, float height,
                                          const renderer::View& view) {
  const std::array<glm::vec4, 4> corners{
      glm::vec4(-0.5f * width, 0.0f, 0.0f, 1.0f), glm::vec4(0.5f * width, 0.0f, 0.0f, 1.0f),
      glm::vec4(-0.5f * width, height, 0.0f, 1.0f), glm::vec4(0.5f * width, height, 0.0f, 1.0f)};
  ImageRect rect{glm::vec2(1e30f), glm::vec2(-1e30f)};
  for (const glm::vec4& corner : corners) {
    const glm::vec4 clip = view.projection * view.view * T_world_label * corner;
    if (!(clip.w > 1e-6f)) return std::nullopt;
    const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
    rect.low = glm::min(rect.low, ndc);
    rect.high = glm::max(rect.high, ndc);
  }
  return rect;
}

glm::mat4 facing_view(const glm::mat4& T_world_label, const renderer::View& view) {
  const glm::mat4 T_world_eye = glm::inverse(view.view);
  const float scale = glm::length(glm::vec3(T_world_label[0]));
  glm::mat4 T(1.0f);
  for (int axis = 0; axis < 3; ++axis)
    T[axis] = glm::vec4(scale * glm::normalize(glm::vec3(T_world_eye[axis])), 0.0f);
  T[3] = T_world_label[3];
  return T;
}

glm::mat4 at_least_lines_tall(const glm::mat4& T_world_label, float width, float height, int lines,
                              const renderer::View& view, float line_fraction) {
  const std::optional<ImageRect> rect = label_image_rect(T_world_label, width, height, view);
  if (!rect || lines <= 0) return T_world_label;
  const float line_ndc = (rect->high.y - rect->low.y) / float(lines);  // NDC: the image is 2 tall
  const float wanted = 2.0f * line_fraction;
  if (!(line_ndc > 0.0f) || line_ndc >= wanted) return T_world_label;
  glm::mat4 T = T_world_label;
  for (int axis = 0; axis < 3; ++axis) T[axis] *= wanted / line_ndc;
  return T;
}

glm::mat4 inside_image(const glm::mat4& T_world_label, float width, float height, const renderer::View& view,
                       float margin) {
  const std::optional<ImageRect> rect = label_image_rect(T_world_label, width, height, view);
  const float p00 = view.projection[0][0], p11 = view.projection[1][1];
  const float depth = -(view.view * T_world_label[3]).z;
  if (!rect || !(depth > 0.0f) || p00 == 0.0f || p11 == 0.0f) return T_world_label;
  // The shift (NDC) that brings each side in; the top-left wins where the panel is larger than the image.
  auto shift = [&](float low, float high) {
    if (high - low > 2.0f - 2.0f * margin) return -1.0f + margin - low;
    if (low < -1.0f + margin) return -1.0f + margin - low;
    if (high > 1.0f - margin) return 1.0f - margin - high;
    return 0.0f;
  };
  const glm::vec2 ndc(shift(rect->low.x, rect->high.x), shift(rect->low.y, rect->high.y));
  if (ndc == glm::vec2(0.0f)) return T_world_label;
  // In eye space at the panel's depth: x_ndc = p00 x_eye / -z_eye, y_ndc = p11 y_eye / -z_eye.
  glm::mat4 move_eye(1.0f);
  move_eye[3] = glm::vec4(ndc.x * depth / p00, ndc.y * depth / p11, 0.0f, 1.0f);
  return glm::inverse(view.view) * move_eye * view.view * T_world_label;
}

glm::mat4 clear_of_hud(const glm::mat4& T_world_label, float width, float height, const ImageRect& hud,
                       const renderer::View& view) {
  const float p11 = view.projection[1][1];
  const float gap = 0.05f * (hud.high.y - hud.low.y);
  glm::mat4 T = T_world_label;
  // The shift is exact for a panel facing the eye; a tilted one (its corners at other depths than its origin)
  // is shifted again until it clears (two more passes at most).
  for (int pass = 0; pass < 3; ++pass) {
    const std::optional<ImageRect> label = label_image_rect(T, width, height, view);
    if (!label) return T;
    const bool overlap = label->low.x < hud.high.x && hud.low.x < label->high.x &&
                         label->low.y < hud.high.y + 0.5f * gap && hud.low.y < label->high.y;
    if (!overlap) return T;
    // Down the image by this much (NDC), then in eye space at the panel's depth: y_ndc = p11 y_eye / -z_eye.
    const float shift_ndc = hud.high.y + gap - label->low.y;
    const glm::vec4 origin_eye = view.view * T[3];
    const float depth = -origin_eye.z;
    if (!(depth > 0.0f) || p11 == 0.0f) return T;
    glm::mat4 move_eye(1.0f);
    move_eye[3] = glm::vec4(0.0f, shift_ndc * depth / p11, 0.0f, 1.0f);
    T = glm::inverse(view.view) * move_eye * view.view * T;
  }
  return T;
}

}  // namespace pushpull::app
