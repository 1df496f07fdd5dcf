#include "helper_thread.hpp"

#include <chrono>

namespace pushpull::deform::detail {
namespace {

// Hand-offs come in bursts within one solver iteration (tens of microseconds apart): spinning this long
// before sleeping avoids a scheduler wake-up per hand-off, at a bounded cost when the other side is slow.
constexpr auto kSpin = std::chrono::microseconds(40);

}  // namespace

template <class Done>
void HelperThread::wait(std::condition_variable& cv, Done done) {
  const auto until = std::chrono::steady_clock::now() + kSpin;
  for (int i = 1; !done(); ++i) {
    if (i % 64 == 0 && std::chrono::steady_clock::now() > until) {
      std::unique_lock lock(mutex_);
      cv.wait(lock, done);
      return;
    }
  }
}

HelperThread::HelperThread() : thread_([this] { loop(); }) {}

HelperThread::~HelperThread() {
  {
    const std::lock_guard lock(mutex_);
    stop_.store(true, std::memory_order_release);
  }
  start_.notify_one();
  thread_.join();
}

void HelperThread::dispatch(Function function, void* context) {
  const std::uint64_t ticket = posted_.load(std::memory_order_relaxed) + 1;
  {
    // Under the lock so that a helper between its check and its sleep cannot miss the notification.
    const std::lock_guard lock(mutex_);
    function_ = function;
    context_ = context;
    posted_.store(ticket, std::memory_order_release);
  }
  start_.notify_one();
  function(context, 0);
  wait(done_, [&] { return finished_.load(std::memory_order_acquire) == ticket; });
}

void HelperThread::loop() {
  std::uint64_t seen = 0;
  for (;;) {
    wait(start_, [&] {
      return stop_.load(std::memory_order_acquire) || posted_.load(std::memory_order_acquire) != seen;
    });
    if (stop_.load(std::memory_order_acquire)) return;
    seen = posted_.load(std::memory_order_acquire);
    function_(context_, 1);  // published by the release of posted_; rewritten only after finished_ == seen
    {
      const std::lock_guard lock(mutex_);
      finished_.store(seen, std::memory_order_release);
    }
    done_.notify_one();
  }
}

}  // namespace pushpull::deform::detail
