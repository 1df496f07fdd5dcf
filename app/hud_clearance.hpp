// Keeping a label in the stage (the readout by the hand) from hiding under a window's heads-up display: where
// a label lands in a view's image, and the same label moved down the image until it clears the HUD.
// Labels are WorldLabel panels: x from -width/2 to width/2 and y from 0 to height in the panel's frame
// (metres, its bottom centre at the origin), placed by T_world_label (world = the view's world, the stage).
// Image positions are Vulkan normalised device coordinates (x right, y down, -1 to 1).
// Thread-safety: pure functions.
#pragma once

#include "pushpull/renderer/types.hpp"

#include <glm/glm.hpp>

#include <optional>

namespace pushpull::app {

struct ImageRect {
  glm::vec2 low{0.0f}, high{0.0f};  // NDC corners, low <= high
};

// The image rectangle the panel covers in `view`, or nullopt when a corner lies behind the eye.
[[nodiscard]] std::optional<ImageRect> label_image_rect(const glm::mat4& T_world_label, float width,
                                                        float height, const renderer::View& view);

// T_world_label moved down the image, in the plane facing the eye at the panel's depth, just far enough for
// its top to clear `hud`'s bottom (with a gap of a twentieth of the HUD's height) when the two overlap;
// unchanged when they do not, or when the panel lies behind the eye.
[[nodiscard]] glm::mat4 clear_of_hud(const glm::mat4& T_world_label, float width, float height,
                                     const ImageRect& hud, const renderer::View& view);

}  // namespace pushpull::app
