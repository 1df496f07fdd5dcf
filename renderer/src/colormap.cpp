#include "pushpull/renderer/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace pushpull::renderer {

glm::vec3 displacement_colour(float t) {
  // Keep in sync with displacement_colour() in shaders/mesh.frag.
  static constexpr std::array<glm::vec3, 6> c{glm::vec3(0.05f, 0.08f, 0.45f), glm::vec3(0.10f, 0.35f, 0.95f),
                                              glm::vec3(0.10f, 0.80f, 0.90f), glm::vec3(0.20f, 0.85f, 0.25f),
                                              glm::vec3(0.98f, 0.85f, 0.10f), glm::vec3(0.85f, 0.08f, 0.05f)};
  const float x = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f) * 5.0f;
  const int i = std::min(static_cast<int>(std::floor(x)), 4);
  return glm::mix(c[i], c[i + 1], x - float(i));
}

glm::vec3 curvature_sign_colour(float k, float eps) {
  if (k > eps) return {0.98f, 0.86f, 0.10f};
  if (k < -eps) return {0.12f, 0.30f, 0.95f};
  return glm::vec3(0.55f);
}

float srgb_to_linear(float e) {
  return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}
float linear_to_srgb(float l) {
  l = std::clamp(l, 0.0f, 1.0f);
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

}  // namespace pushpull::renderer
