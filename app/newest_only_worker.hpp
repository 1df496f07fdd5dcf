// A background thread that works on the newest job only: post() replaces a job not yet started, take() hands
// back the newest finished result. For work whose older inputs are worthless once a newer one exists (turning
// the newest deformation snapshot into vertex data for the frame loop, off the frame's thread).
// Ownership: owns the thread and the function; the destructor waits for a running job and joins.
// Thread-safety: post() and take() may be called from any thread; the function runs on the worker only.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace pushpull::app {

template <class Job, class Result>
class NewestOnlyWorker {
 public:
  // on_start: runs first on the worker's thread (e.g. to pin it to CPUs), when given.
  explicit NewestOnlyWorker(std::function<Result(const Job&)> work, std::function<void()> on_start = {})
      : work_(std::move(work)) {
    thread_ = std::thread([this, on_start = std::move(on_start)] {
      if (on_start) on_start();
      run();
    });
  }
  ~NewestOnlyWorker() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  NewestOnlyWorker(const NewestOnlyWorker&) = delete;
  NewestOnlyWorker& operator=(const NewestOnlyWorker&) = delete;

  // Queues `job`, dropping a queued one that has not started.
  void post(Job job) {
    {
      std::lock_guard lock(mutex_);
      job_ = std::move(job);
    }
    wake_.notify_one();
  }
  // The newest result finished since the last take(), if any (older finished ones are dropped).
  std::optional<Result> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(result_, std::nullopt);
  }
  // Whether a job is queued or running (for tests and shutdown decisions).
  [[nodiscard]] bool busy() const {
    std::lock_guard lock(mutex_);
    return job_.has_value() || running_;
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || job_.has_value(); });
      if (stop_) return;
      Job job = std::move(*job_);
      job_.reset();
      running_ = true;
      lock.unlock();
      Result result = work_(job);
      lock.lock();
      running_ = false;
      result_ = std::move(result);
    }
  }

  std::function<Result(const Job&)> work_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<Job> job_;
  std::optional<Result> result_;
  bool running_ = false;
  bool stop_ = false;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace pushpull::app
