#include "x11_error_guard.hpp"

#include <X11/Xlib.h>
#include <dlfcn.h>

#include <atomic>
#include <cstdio>
#include <exception>
#include <functional>
#include <thread>
#include <utility>

#include <unistd.h>

namespace pushpull::renderer::detail {
namespace {

std::atomic<unsigned long> g_watched{0};  // the watched window's XID (0: none)
std::atomic<bool> g_window_gone{false};
std::atomic<unsigned> g_reported[8]{};  // error codes already printed, 32 per slot

int on_x11_error(Display* display, XErrorEvent* event) {
  const unsigned long watched = g_watched.load();
  if ((event->error_code == BadWindow || event->error_code == BadDrawable) && watched != 0 &&
      event->resourceid == watched) {
    g_window_gone.store(true);
    return 0;
  }
  const unsigned code = event->error_code;
  const unsigned bit = 1u << (code % 32);
  if ((g_reported[code / 32].fetch_or(bit) & bit) == 0) {
    char text[256] = {};
    XGetErrorText(display, event->error_code, text, sizeof(text) - 1);
    std::fprintf(stderr, "pushpull: X error %s (request %d.%d, resource 0x%lx); carrying on\n", text,
                 static_cast<int>(event->request_code), static_cast<int>(event->minor_code),
                 static_cast<unsigned long>(event->resourceid));
  }
  return 0;
}

std::function<void()>& last_words() {
  static std::function<void()> words;
  return words;
}
std::atomic<bool> g_connection_lost{false};
// Whether last words are set, and the thread that set them (the window's: GLFW's main thread); atomics, as
// another thread's handler reads them.
std::atomic<bool> g_has_words{false};
std::atomic<std::thread::id> g_words_thread{};

int on_x11_io_error(Display*) {
  // Another thread's connection (a driver's, a runtime's) found broken first: it waits, while the window's
  // thread meets the error in its next X call and runs the last words; their exit ends this thread too. (The
  // last words use the loop's objects, which only their own thread may touch.)
  if (g_has_words.load() && std::this_thread::get_id() != g_words_thread.load())
    for (;;) ::pause();
  if (g_connection_lost.exchange(true)) return 0;  // a second X call from the last words: exit now
  std::fprintf(
      stderr,
      "pushpull: the connection to the X display was lost (the X server went away, or the window was "
      "force-quit: xkill, a window manager); the process must end\n");
  std::fflush(stderr);
  if (const std::function<void()> words = std::exchange(last_words(), {})) {
    try {
      words();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pushpull: error: %s\n", e.what());
    } catch (...) {
    }
  }
  std::fflush(stdout);
  std::fflush(stderr);
  return 0;  // Xlib then exits with status 1
}

}  // namespace

void install_x11_error_guard() {
  XSetErrorHandler(on_x11_error);
  XSetIOErrorHandler(on_x11_io_error);
}

void set_x11_connection_lost(std::function<void()> words) {
  g_has_words.store(false);
  g_words_thread.store(std::this_thread::get_id());
  last_words() = std::move(words);
  g_has_words.store(static_cast<bool>(last_words()));
}

void watch_x11_window(GLFWwindow* window) {
  // Looked up at run time: GLFW builds without X11 (libglfw3-wayland) have no glfwGetX11Window.
  using GetX11Window = unsigned long (*)(GLFWwindow*);
  const auto get = reinterpret_cast<GetX11Window>(dlsym(RTLD_DEFAULT, "glfwGetX11Window"));
  g_watched.store(get != nullptr && window != nullptr ? get(window) : 0);
  g_window_gone.store(false);
}

bool x11_window_gone() {
  return g_window_gone.load();
}

}  // namespace pushpull::renderer::detail
