// Colour maps of the review overlays, CPU side (legends, tests). mesh.frag implements the same maps.
// Colours are linear RGB in 0..1. Thread-safety: pure functions.
#pragma once

#include <glm/glm.hpp>

namespace pushpull::renderer {

// Displacement magnitude (the paper's Fig. 12, left): t = |d| / scalar_max in 0..1, dark blue at 0
// through blue, cyan, green, yellow to red at 1; clamped outside.
glm::vec3 displacement_colour(float t);

// Sign of the Gaussian curvature (Fig. 12, right): yellow for k > eps, blue for k < -eps, grey otherwise.
glm::vec3 curvature_sign_colour(float k, float eps);

// Review overlays.
inline constexpr glm::vec3 kHandleColour{0.95f, 0.08f, 0.06f};
inline constexpr glm::vec3 kFixedColour{0.10f, 0.25f, 0.95f};
// Magenta: apart from the clay default material, the colour maps (no magenta in either) and the overlays.
inline constexpr glm::vec3 kArrowColour{0.90f, 0.02f, 0.75f};
inline constexpr glm::vec3 kSectionColour{0.05f, 0.05f, 0.05f};

// Linear <-> sRGB-encoded 0..255.
float srgb_to_linear(float encoded01);
float linear_to_srgb(float linear01);

}  // namespace pushpull::renderer
