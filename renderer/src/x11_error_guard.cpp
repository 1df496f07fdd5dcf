#include "x11_error_guard.hpp"

#include <X11/Xlib.h>
#include <dlfcn.h>

#include <atomic>
#include <cstdio>

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

}  // namespace

void install_x11_error_guard() {
  XSetErrorHandler(on_x11_error);
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
