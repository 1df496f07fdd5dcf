#include "interrupt_requests.hpp"

#include <atomic>

namespace pushpull::app {
namespace {

std::atomic<bool> g_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_interrupt(int) {
  g_requested.store(true, std::memory_order_relaxed);
}

}  // namespace

InterruptRequests::InterruptRequests() {
  g_requested.store(false, std::memory_order_relaxed);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // the second signal takes the default action: the process ends
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
