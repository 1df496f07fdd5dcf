// app/newest_only_worker.hpp: newest job wins, newest result is taken once, shutdown joins.
#include "newest_only_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace {

using pushpull::app::NewestOnlyWorker;

template <class Predicate>
bool eventually(Predicate p) {
  for (int i = 0; i < 2000; ++i) {
    if (p()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return p();
}

TEST(NewestOnlyWorker, ReturnsTheResultOfTheNewestJobOnce) {
  NewestOnlyWorker<int, int> worker([](const int& x) { return 2 * x; });
  worker.post(21);
  std::optional<int> r;
  ASSERT_TRUE(eventually([&] { return (r = worker.take()).has_value(); }));
  EXPECT_EQ(*r, 42);
  EXPECT_FALSE(worker.take().has_value());  // taken once
}

TEST(NewestOnlyWorker, AJobPostedWhileAnotherRunsReplacesTheQueuedOneAndTheLastPostedWins) {
  std::atomic<bool> release{false};
  std::atomic<int> started{0};
  NewestOnlyWorker<int, int> worker([&](const int& x) {
    ++started;
    while (x == 1 && !release) std::this_thread::yield();  // the first job blocks until released
    return x;
  });
  worker.post(1);
  ASSERT_TRUE(eventually([&] { return started == 1; }));
  for (int x = 2; x <= 100; ++x) worker.post(x);  // queued while 1 runs: each replaces the previous
  release = true;
  std::optional<int> last;
  ASSERT_TRUE(eventually([&] {
    if (auto r = worker.take()) last = r;
    return last == 100 && !worker.busy();
  }));
  EXPECT_EQ(started, 2);  // 1, then only the newest queued job (100)
}

TEST(NewestOnlyWorker, DestructionWaitsForTheRunningJob) {
  std::atomic<bool> started{false}, finished{false};
  {
    NewestOnlyWorker<int, int> worker([&](const int& x) {
      started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      finished = true;
      return x;
    });
    worker.post(1);
    ASSERT_TRUE(eventually([&] { return started.load(); }));
  }
  EXPECT_TRUE(finished);
}

}  // namespace
