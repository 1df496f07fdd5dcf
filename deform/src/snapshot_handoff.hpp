// Private: the newest-value slot between the deformation worker (one writer) and the frame loop (readers).
//
// A shared_ptr guarded by a spin flag that is held for one pointer copy or swap (tens of nanoseconds), never
// while anything is computed; the value a store replaces is released after the flag is dropped, so a
// snapshot's destruction never delays a reader. This is what std::atomic<std::shared_ptr> does in
// libstdc++ 12, written out because that implementation's lock bit is invisible to ThreadSanitizer (it
// reports its own internals as races) and a sanitizer-clean service is part of the test suite.
// Thread-safety: load() and store() may be called from any thread concurrently.
#pragma once

#include <atomic>
#include <memory>
#include <thread>
#include <utility>

namespace pushpull::deform::detail {

template <class T>
class NewestValue {
 public:
  [[nodiscard]] std::shared_ptr<T> load() const {
    lock();
    std::shared_ptr<T> copy = value_;
    unlock();
    return copy;
  }

  void store(std::shared_ptr<T> next) {
    lock();
    value_.swap(next);
    unlock();
    // `next` now holds the previous value: released here, outside the flag.
  }

 private:
  void lock() const {
    for (int spins = 0; flag_.test_and_set(std::memory_order_acquire); ++spins) {
      if (spins > 64) std::this_thread::yield();  // the holder was preempted: give it the core
    }
  }
  void unlock() const { flag_.clear(std::memory_order_release); }

  mutable std::atomic_flag flag_ = ATOMIC_FLAG_INIT;
  std::shared_ptr<T> value_;
};

}  // namespace pushpull::deform::detail
