// app/signals_held: a SIGTERM, SIGINT or SIGHUP that arrives while a pair of files is written is acted on
// after both are written (a deform interrupted between its model and its metrics left a new model beside no
// metrics); a second one at once; one held while a write fails waits until the error is said.
#include "signals_held.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

fs::path test_dir() {
  const fs::path dir = fs::temp_directory_path() / ("pushpull_signals_held_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

// Runs `body` in a child process whose three signals have their default action (a test run under nohup or
// as a background job inherits them ignored) and returns the child's wait status.
template <class Body>
int child_status(Body body) {
  const pid_t pid = fork();
  if (pid == 0) {
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, SIG_DFL);
    body();
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(SignalsHeld, ASignalDuringThePairIsActedOnAfterIt) {
  const fs::path dir = test_dir();
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    const fs::path second = dir / ("second-" + std::to_string(signal));
    const int status = child_status([&] {
      SignalsHeld held;
      std::raise(signal);  // as if sent between the two writes
      std::ofstream(second) << "written\n";
    });
    EXPECT_TRUE(fs::exists(second)) << "the second file is written before the signal is acted on";
    ASSERT_TRUE(WIFSIGNALED(status)) << status;
    EXPECT_EQ(WTERMSIG(status), signal);
  }
  fs::remove_all(dir);
}

TEST(SignalsHeld, ASecondSignalIsActedOnAtOnce) {
  const fs::path dir = test_dir();
  const fs::path after = dir / "after";
  const int status = child_status([&] {
    SignalsHeld held;
    std::raise(SIGTERM);
    std::raise(SIGINT);  // a write that hangs can still be interrupted
    std::ofstream(after) << "not reached\n";
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_FALSE(fs::exists(after));
  fs::remove_all(dir);
}

TEST(SignalsHeld, ASignalHeldWhileAWriteFailsWaitsForTheErrorToBeSaid) {
  const fs::path dir = test_dir();
  const fs::path said = dir / "said";
  const int status = child_status([&] {
    try {
      SignalsHeld held;
      std::raise(SIGTERM);
      throw std::runtime_error("the write failed");
    } catch (const std::exception& e) {
      std::ofstream(said) << e.what() << "\n";  // as main prints the error
      raise_held_signal();
    }
  });
  EXPECT_TRUE(fs::exists(said));
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  fs::remove_all(dir);
}

TEST(SignalsHeld, WithoutASignalNothingHappensAndTheHandlersComeBack) {
  struct sigaction before {};
  sigaction(SIGTERM, nullptr, &before);
  { SignalsHeld held; }
  struct sigaction after {};
  sigaction(SIGTERM, nullptr, &after);
  EXPECT_EQ(before.sa_handler, after.sa_handler);
  raise_held_signal();  // nothing pending: nothing happens
}

}  // namespace
}  // namespace pushpull::app
