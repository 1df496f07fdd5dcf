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

// The panel turned to face `view`'s eye: parallel to its image plane, its text along the image's x and its
// lines up the image, about the same bottom centre and at the same size. The readout by the hand faces the
// headset; a window's own view (smoothed first person, free orbit) saw it edge-on or at a slant.
[[nodiscard]] glm::mat4 facing_view(const glm::mat4& T_world_label, const renderer::View& view);

// A panel facing the eye (facing_view) of `lines` lines, scaled about its bottom centre so that a line is at
// least `line_fraction` of the image's height (it keeps its size where it is larger): the readout by the hand
// is sized for the headset, and a window's view from farther off showed it a few pixels tall. Unchanged when
// it lies behind the eye.
[[nodiscard]] glm::mat4 at_least_lines_tall(const glm::mat4& T_world_label, float width, float height,
                                            int lines, const renderer::View& view, float line_fraction);

// A panel facing the eye (facing_view) moved in its plane, at its depth, just far enough to lie inside the
// image with a margin of `margin` (NDC); where it is larger than the image, its top-left corner inside.
// Unchanged when it lies behind the eye. (The readout by a hand held low left the window's bottom edge.)
[[nodiscard]] glm::mat4 inside_image(const glm::mat4& T_world_label, float width, float height,
                                     const renderer::View& view, float margin);

// T_world_label moved down the image, in the plane facing the eye at the panel's depth, just far enough for
// its top to clear `hud`'s bottom (with a gap of a twentieth of the HUD's height) when the two overlap;
// unchanged when they do not, or when the panel lies behind the eye.
[[nodiscard]] glm::mat4 clear_of_hud(const glm::mat4& T_world_label, float width, float height,
                                     const ImageRect& hud, const renderer::View& view);

}  // namespace pushpull::app
