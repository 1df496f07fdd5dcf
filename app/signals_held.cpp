#include "signals_held.hpp"

#include <atomic>

namespace pushpull::app {
namespace {

constexpr int kHeld[3] = {SIGINT, SIGTERM, SIGHUP};
std::atomic<int> held_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

void hold(int signal) {
  int none = 0;
  held_signal.compare_exchange_strong(none, signal);  // the first one is acted on
}

}  // namespace

SignalsHeld::SignalsHeld() {
  held_signal.store(0);
  struct sigaction action {};
  action.sa_handler = hold;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int i = 0; i < 3; ++i) sigaction(kHeld[i], &action, &previous_[i]);
}

SignalsHeld::~SignalsHeld() {
  for (int i = 0; i < 3; ++i) sigaction(kHeld[i], &previous_[i], nullptr);
  if (const int signal = held_signal.exchange(0); signal != 0) std::raise(signal);
}

}  // namespace pushpull::app
