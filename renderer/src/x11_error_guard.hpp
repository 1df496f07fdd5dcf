// Private: Xlib's default error handler prints the error and exits the process. A mirror or desktop window
// destroyed from outside (xdotool windowclose, a crashed or absent window manager) makes GLFW's next request
// on it fail with BadWindow, and the review died with exit 1 before or while writing its --out model.
// install_x11_error_guard() puts a handler in its place that records a BadWindow or BadDrawable on a watched
// window (the window is gone: MirrorWindow then reads as lost and closed) and prints any other X error once
// per error code ("X error ...; carrying on"), never exiting.
// Ownership: the handler is process-wide and stays installed: it replaces whatever handler another library in
// the process set (an OpenXR runtime's, say), and X errors that used to end the process are printed instead.
// GLFW 3.3 resets the handler to Xlib's default after its own guarded requests (window creation, ...), so
// MirrorWindow installs it again after every poll. Harmless where GLFW does not use X11 (never called there).
// Thread-safety: the watched window and the flag are atomic; install from the main thread (GLFW's rule).
//
// The connection itself breaking (the X server gone, the client killed by xkill or a window manager's force
// quit, an ssh -X link dropped) is fatal in Xlib: the process exits when its I/O error handler returns. The
// guard's I/O error handler says so and first calls the last words set with set_x11_connection_lost (once),
// so that the review can write its committed work.
#pragma once

#include <functional>

struct GLFWwindow;

namespace pushpull::renderer::detail {

void install_x11_error_guard();
// Watches `window`'s X11 window (none when GLFW does not run on X11) and clears the flag below.
void watch_x11_window(GLFWwindow* window);
// A BadWindow or BadDrawable error on the watched window has arrived since watch_x11_window.
[[nodiscard]] bool x11_window_gone();
// What to do before the process exits on a broken connection (empty: nothing); called on the thread whose X
// call found it broken, once. Set and cleared from the main thread.
void set_x11_connection_lost(std::function<void()> last_words);

}  // namespace pushpull::renderer::detail
