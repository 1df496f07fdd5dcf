// pushpull::renderer::MirrorWindow: the supervisor's desktop mirror, a GLFW window with a Vulkan
// swapchain that the Renderer draws into like any other target.
//
// Setup: the instance needs the surface extensions GLFW names and the device VK_KHR_swapchain:
//   ContextOptions o; o.instance_extensions = MirrorWindow::required_instance_extensions(); o.swapchain =
//   true;
// Per frame:
//   if (auto frame = window.acquire()) { renderer.render(views, draws, settings, frame->targets,
//   frame->sync);
//                                         window.present(*frame); }
// acquire() returns nullopt while the window is minimised, the swapchain was just recreated, no image came
// within its timeout (100 ms by default; a headset's mirror asks for 0: a window that is not ready skips
// that mirror frame instead of holding up the headset's), or the window is lost().
//
// Ownership: owns the window, surface and swapchain; borrows the Context (must outlive it).
// Thread-safety: GLFW requires the main thread; the renderer's thread rule applies too.
// GLFW stays initialised for the life of the process (glfwTerminate is left to the application).
#pragma once

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/renderer.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::renderer {

class MirrorWindow {
 public:
  // Initialises GLFW; throws VulkanError when there is no display or no Vulkan support in GLFW.
  static std::vector<std::string> required_instance_extensions();

  MirrorWindow(const Context& context, uint32_t width, uint32_t height, const std::string& title);
  ~MirrorWindow();
  MirrorWindow(const MirrorWindow&) = delete;
  MirrorWindow& operator=(const MirrorWindow&) = delete;

  struct Frame {
    RenderTargets targets;  // one view, left in PRESENT_SRC_KHR
    FrameSync sync;         // wait: image acquired; signal: rendering done (present waits on it)
    uint32_t image_index = 0;
  };
  std::optional<Frame> acquire(uint64_t timeout_ns = 100'000'000);
  void present(const Frame& frame);
  // A frame acquired and never presented (the loop's frame threw in between): its image stays acquired and
  // its semaphores may be left signalled, so the swapchain and its semaphores are made again before the next
  // acquire (which waits for the device to go idle, an error path only).
  void abandon(const Frame& frame);

  // The user closed the window, or it is lost().
  [[nodiscard]] bool should_close() const;
  // The window was destroyed from outside (an X11 BadWindow, or the surface lost): acquire() returns nullopt
  // from then on and the loop should end as on a close. X errors no longer end the process
  // (src/x11_error_guard.hpp).
  [[nodiscard]] bool lost() const;
  // What to do when the connection to the X display breaks (the X server gone, the window force-quit with
  // xkill): Xlib then ends the process with status 1 as soon as `last_words` returns, so they are the last
  // chance to keep the user's work. Called once, on the main thread, inside poll_events() or another window
  // call; they must not use this window. Unset when the returned LastWords goes (declare it after everything
  // the last words use, so that it goes first) or with the window. Nothing happens without X11.
  class LastWords {
   public:
    LastWords(LastWords&& other) noexcept : set_(std::exchange(other.set_, false)) {}
    LastWords& operator=(LastWords&&) = delete;
    ~LastWords();

   private:
    friend class MirrorWindow;
    LastWords() = default;
    bool set_ = true;
  };
  [[nodiscard]] LastWords on_connection_lost(std::function<void()> last_words);
  void poll_events();
  // Keys pressed since the last call, in order, as GLFW key codes (letters and digits are their ASCII
  // upper-case characters, e.g. 'C'; GLFW_KEY_ESCAPE = 256). Filled by poll_events().
  std::vector<int> take_key_presses();
  void set_title(const std::string& title);

  // The mouse as of the last poll_events(), the same until the next: cursor in window coordinates (pixels
  // from the top-left corner, window_width x window_height, which may differ from extent() on scaled
  // displays), buttons, the shift key, and the scroll since the poll before (lines, + = away from the user).
  // Button presses and releases are not lost between polls: each poll shows the next one not yet shown,
  // as it was when it happened (a release first as the position it happened at, the button still held,
  // then released), and the live state once none is left; a click within one frame is a press one frame and
  // a release two frames later. (At most 32 wait: past that, from a loop that stopped polling, the oldest
  // go.)
  struct Pointer {
    double x = 0.0, y = 0.0;
    int window_width = 1, window_height = 1;
    bool left = false, right = false, middle = false, shift = false;
    // `left` is held in this snapshot but its release is already queued (the button is up by now): a key
    // that acts between drags may go ahead, the drag ends within two polls.
    bool left_release_queued = false;
    double scroll = 0.0;
  };
  [[nodiscard]] Pointer pointer() const;
  [[nodiscard]] VkExtent2D extent() const;
  // Whether the swapchain images take transfers (Renderer::RenderPass::blit_from can fill them).
  [[nodiscard]] bool accepts_blit() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pushpull::renderer
