// Private: Xlib's default error handler prints the error and exits the process. A mirror or desktop window
// destroyed from outside (xdotool windowclose, a crashed or absent window manager) makes GLFW's next request
// on it fail with BadWindow, and the review died with exit 1 before or while writing its --out model.
// install_x11_error_guard() puts a handler in its place that records BadWindow and BadDrawable (the window is
// gone: MirrorWindow then reads as closed) and prints any other X error once per error code, never exiting.
// GLFW 3.3 resets the handler to Xlib's default after its own guarded requests (window creation, ...), so
// MirrorWindow installs it again after every poll. Harmless where GLFW does not use X11 (the handler is never
// called).
// Thread-safety: the flag is atomic; install from the main thread (GLFW's rule).
#pragma once

namespace pushpull::renderer::detail {

void install_x11_error_guard();
// A BadWindow or BadDrawable error has arrived since the last reset.
[[nodiscard]] bool x11_window_gone();
void reset_x11_window_gone();

}  // namespace pushpull::renderer::detail
