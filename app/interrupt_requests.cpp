#include "interrupt_requests.hpp"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace pushpull::app {
namespace {

std::atomic<bool> g_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_interrupt(int signal_number) {
  if (!g_requested.exchange(true, std::memory_order_relaxed)) return;
  // The second: the process ends at once by the signal's default action, said first (write is
  // async-signal-safe; a failed write changes nothing).
  static constexpr char kSaid[] =
      "\npushpull: quitting at once (a second interrupt): what was not yet written is lost (`pushpull "
      "replay` "
      "of the session recording rebuilds the committed model)\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kSaid, sizeof kSaid - 1);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

InterruptRequests::InterruptRequests() {
  g_requested.store(false, std::memory_order_relaxed);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // the second signal: on_interrupt says so, then the default action ends the process
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

InterruptRequests::~InterruptRequests() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

bool InterruptRequests::requested() const {
  return g_requested.load(std::memory_order_relaxed);
}

}  // namespace pushpull::app
