// The GLFW mirror: runs when a display is available (CI: xvfb-run), skipped otherwise.
#include "pushpull/renderer/mirror_window.hpp"
#include "test_scenes.hpp"

#include <cstdlib>

namespace pushpull::renderer {
namespace {

TEST(MirrorWindow, PresentsFramesWithoutValidationMessages) {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
    GTEST_SKIP() << "no display (run under xvfb-run to test the mirror window)";
  ContextOptions options;
  options.validation = true;
  options.instance_extensions = MirrorWindow::required_instance_extensions();
  options.swapchain = true;
  Context context = Context::create(options);
  {
    Renderer renderer(context);
    MirrorWindow window(context, 320, 240, "pushpull mirror test");
    const MeshId mesh = renderer.add_mesh(testing::make_sphere(1.0f, 24, 48));
    const Bounds bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
    const View view = frame_bounds(bounds, OrbitCamera{}, 320.0f / 240.0f);
    const Draw draw{mesh, glm::mat4(1.0f)};
    int presented = 0;
    for (int i = 0; i < 10; ++i) {
      window.poll_events();
      if (auto frame = window.acquire()) {
        renderer.render(std::span(&view, 1), std::span(&draw, 1), FrameSettings{}, frame->targets,
                        frame->sync);
        window.present(*frame);
        ++presented;
      }
    }
    renderer.wait_idle();
    EXPECT_GE(presented, 8);
  }
  EXPECT_EQ(context.validation_message_count(), 0u);
}

}  // namespace
}  // namespace pushpull::renderer
