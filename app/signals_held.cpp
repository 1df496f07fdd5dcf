#include "signals_held.hpp"

#include <atomic>
#include <exception>

namespace pushpull::app {
namespace {

constexpr int kHeld[3] = {SIGINT, SIGTERM, SIGHUP};
std::atomic<int> held_signal{0};     // the first signal while held
std::atomic<int> pending_signal{0};  // held, its holder gone by an exception: for raise_held_signal()
static_assert(std::atomic<int>::is_always_lock_free);

}  // namespace

// A second signal while one is held: its default action at once (sigaction and raise are async-signal-safe).
extern "C" void pushpull_hold_signal(int signal_number) {
  int none = 0;
  if (held_signal.compare_exchange_strong(none, signal_number)) return;
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(signal_number, &fallback, nullptr);
  std::raise(signal_number);
}

SignalsHeld::SignalsHeld() : exceptions_(std::uncaught_exceptions()) {
  held_signal.store(0);
  struct sigaction action {};
  action.sa_handler = pushpull_hold_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int i = 0; i < 3; ++i) sigaction(kHeld[i], &action, &previous_[i]);
}

SignalsHeld::~SignalsHeld() {
  for (int i = 0; i < 3; ++i) sigaction(kHeld[i], &previous_[i], nullptr);
  const int signal_number = held_signal.exchange(0);
  if (signal_number == 0) return;
  if (std::uncaught_exceptions() > exceptions_)
    pending_signal.store(signal_number);
  else
    std::raise(signal_number);
}

void raise_held_signal() {
  if (const int signal_number = pending_signal.exchange(0); signal_number != 0) std::raise(signal_number);
}

}  // namespace pushpull::app
