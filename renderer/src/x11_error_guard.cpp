#include "x11_error_guard.hpp"

#include <X11/Xlib.h>

#include <atomic>
#include <cstdio>

namespace pushpull::renderer::detail {
namespace {

std::atomic<bool> g_window_gone{false};
std::atomic<unsigned> g_reported[8]{};  // error codes already printed, as bits of 32 per slot

int on_x11_error(Display* display, XErrorEvent* event) {
  if (event->error_code == BadWindow || event->error_code == BadDrawable) {
    g_window_gone.store(true);
    return 0;
  }
  const unsigned code = event->error_code;
  const unsigned bit = 1u << (code % 32);
  if (code < 256 && (g_reported[code / 32].fetch_or(bit) & bit) == 0) {
    char text[256] = {};
    XGetErrorText(display, event->error_code, text, sizeof(text) - 1);
    std::fprintf(stderr, "pushpull: X error %s (request %d.%d); carrying on\n", text,
                 static_cast<int>(event->request_code), static_cast<int>(event->minor_code));
  }
  return 0;
}

}  // namespace

void install_x11_error_guard() {
  XSetErrorHandler(on_x11_error);
}

bool x11_window_gone() {
  return g_window_gone.load();
}

void reset_x11_window_gone() {
  g_window_gone.store(false);
}

}  // namespace pushpull::renderer::detail
