// The generalised winding number that tells a camera inside a model (CPU only).
#include "pushpull/renderer/geometry.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

namespace pushpull::renderer {
namespace {

TEST(Geometry, WindingNumberIsOneInsideAClosedSurfaceAndZeroOutside) {
  const RenderMesh sphere = testing::make_sphere(1.0f, 24, 48);
  EXPECT_NEAR(winding_number(sphere.positions, sphere.indices, glm::vec3(0.0f)), 1.0, 1e-6);
  EXPECT_NEAR(winding_number(sphere.positions, sphere.indices, glm::vec3(0.3f, -0.5f, 0.2f)), 1.0, 1e-6);
  EXPECT_NEAR(winding_number(sphere.positions, sphere.indices, glm::vec3(0.0f, 0.0f, 3.0f)), 0.0, 1e-6);
  EXPECT_NEAR(winding_number(sphere.positions, sphere.indices, glm::vec3(1.2f, 0.0f, 0.0f)), 0.0, 1e-6);
  // An open sheet: never "inside", about +-1/2 right above or below its middle.
  const RenderMesh sheet = testing::make_sheet(8);
  EXPECT_LT(std::abs(winding_number(sheet.positions, sheet.indices, glm::vec3(0.0f, 0.0f, 1e-3f))), 0.51);
}

}  // namespace
}  // namespace pushpull::renderer
