// Integration-test helper: runs a shell command (or the `pushpull` executable built with the tests) and
// captures its exit status and its stdout and stderr together. Blocking; safe to call from any test.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace pushpull::testing {

struct CommandResult {
  int status = -1;     // exit status, -1 when the command could not run or was killed
  std::string output;  // stdout and stderr together
};

inline CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int raw = ::pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return result;
}

// `pushpull ARGUMENTS` (the arguments are passed through the shell as written).
inline CommandResult run_pushpull(const std::string& arguments) {
  return run_command(std::string(PUSHPULL_EXECUTABLE) + " " + arguments);
}

}  // namespace pushpull::testing
