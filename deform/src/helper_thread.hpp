// Private: one persistent helper thread for splitting a loop in two fixed halves ("part 0" on the calling
// thread, "part 1" on the helper). Used by the solver's local step, triangular solves, Anderson acceleration
// and error estimate; no dependency beyond the standard library.
//
// Contract: run_both(job) calls job(0) on the calling thread and job(1) on the helper, and returns once
// both have returned; writes made by job(1) happen-before run_both returns. The job must not throw (an
// exception escaping job(1) terminates the program) and the two parts must write disjoint memory.
// Thread-safety: one HelperThread serves one caller at a time; run_both must not be called concurrently
// on the same object, nor from inside a job. Construction starts the thread, destruction joins it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>

namespace pushpull::deform::detail {

class HelperThread {
 public:
  HelperThread();
  ~HelperThread();
  HelperThread(const HelperThread&) = delete;
  HelperThread& operator=(const HelperThread&) = delete;

  template <class Job>
  void run_both(Job& job) {
    dispatch([](void* context, int part) { (*static_cast<Job*>(context))(part); }, &job);
  }

 private:
  using Function = void (*)(void*, int);
  void dispatch(Function function, void* context);
  void loop();

  // Waits (briefly spinning, then blocking on the condition variable) until done() holds.
  template <class Done>
  void wait(std::condition_variable& cv, Done done);

  std::mutex mutex_;
  std::condition_variable start_, done_;
  Function function_ = nullptr;  // written before posted_ is released, read after it is acquired
  void* context_ = nullptr;
  std::atomic<std::uint64_t> posted_{0}, finished_{0};  // jobs handed to the helper / completed by it
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started once the members above exist
};

// The two fixed halves [half_begin, half_end) of n entries that run_halves' parts take, split at a multiple
// of `multiple` (3 keeps a vertex's coordinates together): the same split whatever the thread count.
inline std::ptrdiff_t half_begin(int part, std::ptrdiff_t n, std::ptrdiff_t multiple = 1) {
  return part == 0 ? 0 : multiple * ((n / multiple) / 2);
}
inline std::ptrdiff_t half_end(int part, std::ptrdiff_t n, std::ptrdiff_t multiple = 1) {
  return part == 0 ? multiple * ((n / multiple) / 2) : n;
}

// job(0) then job(1): on the two threads when `threads` is given, else one after the other on the calling
// thread (the same parts, so the same results either way).
template <class Job>
void run_halves(HelperThread* threads, Job& job) {
  if (threads) {
    threads->run_both(job);
  } else {
    job(0);
    job(1);
  }
}

}  // namespace pushpull::deform::detail
