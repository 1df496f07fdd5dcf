// app/signals_held: a SIGTERM or SIGINT that arrives while a pair of files is written is acted on after both
// are written (a deform interrupted between its model and its metrics left a new model beside no metrics).
#include "signals_held.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

namespace pushpull::app {
namespace {

namespace fs = std::filesystem;

// In a child process: holds the signals, raises `signal` (as if sent between the two writes), writes the
// second file, lets go. Returns the child's wait status.
int child_status_after(int signal, const fs::path& second) {
  const pid_t pid = fork();
  if (pid == 0) {
    {
      SignalsHeld held;
      std::raise(signal);
      std::ofstream(second) << "written\n";
    }
    _exit(0);  // not reached: the held signal ends the process
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(SignalsHeld, ASignalDuringThePairIsActedOnAfterIt) {
  const fs::path dir = fs::temp_directory_path() / "pushpull_signals_held_test";
  fs::create_directories(dir);
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    const fs::path second = dir / ("second-" + std::to_string(signal));
    fs::remove(second);
    const int status = child_status_after(signal, second);
    EXPECT_TRUE(fs::exists(second)) << "the second file is written before the signal is acted on";
    ASSERT_TRUE(WIFSIGNALED(status)) << status;
    EXPECT_EQ(WTERMSIG(status), signal);
  }
}

TEST(SignalsHeld, WithoutASignalNothingHappensAndTheHandlersComeBack) {
  struct sigaction before {};
  sigaction(SIGTERM, nullptr, &before);
  { SignalsHeld held; }
  struct sigaction after {};
  sigaction(SIGTERM, nullptr, &after);
  EXPECT_EQ(before.sa_handler, after.sa_handler);
}

}  // namespace
}  // namespace pushpull::app
