// The readout by the hand in the supervisor's mirror: where it would lie under the HUD (the window's top-left
// panel), it is drawn moved down the image just clear of it; elsewhere exactly where it stands.
#include "hud_clearance.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

using pushpull::app::clear_of_hud;
using pushpull::app::ImageRect;
using pushpull::app::label_image_rect;

// A camera at the origin looking down -Z, +Y up, 60 degrees vertically, square image, Vulkan's y-down clip
// space (renderer/camera.cpp's convention).
pushpull::renderer::View camera() {
  pushpull::renderer::View view;
  glm::mat4 p = glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 100.0f);
  p[1][1] *= -1.0f;
  view.projection = p;
  return view;
}

// A panel 0.2 x 0.1 m facing the camera with its bottom centre at `at`.
glm::mat4 panel_at(const glm::vec3& at) {
  return glm::translate(glm::mat4(1.0f), at);
}

TEST(HudClearance, APanelUnderTheHudMovesDownJustClearOfIt) {
  const auto view = camera();
  const ImageRect hud{{-1.0f, -1.0f}, {-0.2f, -0.6f}};  // the top-left corner of the image
  // Up and left in the image, 2 m away: under the HUD.
  const glm::mat4 T = panel_at({-0.8f, 0.7f, -2.0f});
  const auto before = label_image_rect(T, 0.2f, 0.1f, view);
  ASSERT_TRUE(before);
  ASSERT_LT(before->low.y, hud.high.y);
  ASSERT_LT(before->low.x, hud.high.x);
  const glm::mat4 moved = clear_of_hud(T, 0.2f, 0.1f, hud, view);
  const auto after = label_image_rect(moved, 0.2f, 0.1f, view);
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->low.y, hud.high.y + 0.05f * 0.4f, 1e-4f);  // just below, a twentieth of the HUD apart
  EXPECT_NEAR(after->low.x, before->low.x, 1e-4f);              // straight down the image
  EXPECT_NEAR(after->high.x - after->low.x, before->high.x - before->low.x, 1e-4f);
  EXPECT_NEAR(moved[3].z, T[3].z, 1e-5f);  // at the same depth
}

TEST(HudClearance, APanelElsewhereOrBehindTheEyeStaysWhereItIs) {
  const auto view = camera();
  const ImageRect hud{{-1.0f, -1.0f}, {-0.2f, -0.6f}};
  for (const glm::vec3 at : {glm::vec3(0.5f, -0.5f, -2.0f), glm::vec3(-0.8f, 0.7f, 2.0f)}) {
    const glm::mat4 T = panel_at(at);
    EXPECT_EQ(clear_of_hud(T, 0.2f, 0.1f, hud, view), T);
  }
  EXPECT_FALSE(label_image_rect(panel_at({0.0f, 0.0f, 2.0f}), 0.2f, 0.1f, view));  // behind the eye
}

// The same from a camera turned and moved in the stage (the orbit view), the panel tilted away from it (the
// readout faces the head, not the mirror's camera): moved in the camera's frame, straight down its image,
// until it clears the HUD, and no further than a little past the gap.
TEST(HudClearance, ATiltedPanelSeenFromATurnedCameraClearsTheHud) {
  auto view = camera();
  view.view =
      glm::lookAt(glm::vec3(1.0f, 1.6f, 2.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const ImageRect hud{{-1.0f, -1.0f}, {-0.2f, -0.6f}};
  // 2 m in front of the camera, at image position (-0.6, -0.75): under the HUD.
  const float depth = 2.0f;
  const glm::vec4 eye_point(-0.6f * depth / view.projection[0][0], -0.75f * depth / view.projection[1][1],
                            -depth, 1.0f);
  const glm::vec3 at = glm::vec3(glm::inverse(view.view) * eye_point);
  const glm::mat4 T = glm::rotate(
      glm::rotate(glm::translate(glm::mat4(1.0f), at), glm::radians(50.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
      glm::radians(35.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  const auto before = label_image_rect(T, 0.2f, 0.1f, view);
  ASSERT_TRUE(before);
  ASSERT_LT(before->low.y, hud.high.y);
  const glm::mat4 moved = clear_of_hud(T, 0.2f, 0.1f, hud, view);
  const auto after = label_image_rect(moved, 0.2f, 0.1f, view);
  ASSERT_TRUE(after);
  EXPECT_GE(after->low.y, hud.high.y);                        // clear of the HUD
  EXPECT_LE(after->low.y, hud.high.y + 2.0f * 0.05f * 0.4f);  // by no more than about its gap
  // Moved along the camera's up axis only: the same x and depth in the camera's frame, the same orientation.
  const glm::vec4 from = view.view * T[3], to = view.view * moved[3];
  EXPECT_NEAR(to.x, from.x, 1e-5f);
  EXPECT_NEAR(to.z, from.z, 1e-5f);
  EXPECT_LT(to.y, from.y - 1e-3f);  // down the image (Vulkan's y runs down) is down the camera's y
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(moved[c][r], T[c][r], 1e-5f);
}

// A window's own view sees the readout facing the headset, at a slant; turned to face the view, it keeps its
// place and size, and lies parallel to the image with its text along the image's x.
TEST(HudClearance, APanelTurnedToFaceTheViewKeepsItsPlaceAndSize) {
  const auto view = camera();
  const glm::mat4 tilted = glm::rotate(glm::scale(panel_at({0.3f, -0.4f, -2.0f}), glm::vec3(1.5f)),
                                       glm::radians(60.0f), glm::vec3(1.0f, 0.3f, 0.0f));
  const glm::mat4 facing = pushpull::app::facing_view(tilted, view);
  for (int r = 0; r < 3; ++r) EXPECT_FLOAT_EQ(facing[3][r], tilted[3][r]);  // the same bottom centre
  EXPECT_NEAR(facing[0][0], 1.5f, 1e-5f);                                   // text along +x, the same size
  EXPECT_NEAR(facing[1][1], 1.5f, 1e-5f);                                   // lines up +y
  EXPECT_NEAR(facing[2][2], 1.5f, 1e-5f);                                   // facing the eye (+z)
  // Its image: as wide as a 0.3 x 0.15 m panel 2 m away is (no slant foreshortens it).
  const auto rect = label_image_rect(facing, 0.2f, 0.1f, view);
  ASSERT_TRUE(rect);
  const float expected_width = 0.3f / 2.0f * view.projection[0][0];
  EXPECT_NEAR(rect->high.x - rect->low.x, expected_width, 1e-4f);
}

// Seen from farther off than the headset sees it, the readout is scaled up about its bottom centre until a
// line is the height asked for; a panel already as tall keeps its size.
TEST(HudClearance, APanelTooSmallInTheImageIsScaledUpToALineHeight) {
  const auto view = camera();
  const glm::mat4 far = panel_at({0.2f, 0.0f, -20.0f});  // two lines of 0.05 m, 20 m away
  const auto before = label_image_rect(far, 0.2f, 0.1f, view);
  ASSERT_TRUE(before);
  ASSERT_LT((before->high.y - before->low.y) / 2.0f, 2.0f * 0.02f);
  const glm::mat4 scaled = pushpull::app::at_least_lines_tall(far, 0.2f, 0.1f, 2, view, 0.02f);
  const auto after = label_image_rect(scaled, 0.2f, 0.1f, view);
  ASSERT_TRUE(after);
  EXPECT_NEAR((after->high.y - after->low.y) / 2.0f, 2.0f * 0.02f, 1e-4f);
  for (int r = 0; r < 3; ++r) EXPECT_FLOAT_EQ(scaled[3][r], far[3][r]);
  const glm::mat4 near = panel_at({0.2f, 0.0f, -0.5f});
  EXPECT_EQ(pushpull::app::at_least_lines_tall(near, 0.2f, 0.1f, 2, view, 0.02f), near);
}

// A readout by a hand held low (below the image's bottom edge) is moved up just inside it; one inside stays;
// one larger than the image shows its top-left corner.
TEST(HudClearance, APanelOutsideTheImageIsMovedJustInside) {
  const auto view = camera();
  const float margin = 0.02f;
  const glm::mat4 low = panel_at({0.1f, -2.0f, -2.0f});  // far below: image y > 1 (Vulkan's y is down)
  const auto before = label_image_rect(low, 0.2f, 0.1f, view);
  ASSERT_TRUE(before);
  ASSERT_GT(before->low.y, 1.0f);
  const glm::mat4 moved = pushpull::app::inside_image(low, 0.2f, 0.1f, view, margin);
  const auto after = label_image_rect(moved, 0.2f, 0.1f, view);
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->high.y, 1.0f - margin, 1e-4f);  // just inside the bottom edge
  EXPECT_NEAR(after->low.x, before->low.x, 1e-5f);   // not moved sideways
  EXPECT_NEAR(moved[3][2], low[3][2], 1e-5f);        // at its depth
  const glm::mat4 inside = panel_at({0.1f, 0.1f, -2.0f});
  EXPECT_EQ(pushpull::app::inside_image(inside, 0.2f, 0.1f, view, margin), inside);
  const auto huge =
      label_image_rect(pushpull::app::inside_image(inside, 20.0f, 10.0f, view, margin), 20.0f, 10.0f, view);
  ASSERT_TRUE(huge);
  EXPECT_NEAR(huge->low.x, -1.0f + margin, 1e-4f);
  EXPECT_NEAR(huge->low.y, -1.0f + margin, 1e-4f);
  // Behind the eye: left as it is.
  const glm::mat4 behind = panel_at({0.0f, 0.0f, 2.0f});
  EXPECT_EQ(pushpull::app::inside_image(behind, 0.2f, 0.1f, view, margin), behind);
}

}  // namespace
