#include "messages_off_stdout.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>

namespace pushpull::app {

bool names_stdout(const std::string& path) {
  if (path.empty()) return false;
  struct stat out {};
  struct stat named {};
  if (fstat(STDOUT_FILENO, &out) != 0 || stat(path.c_str(), &named) != 0) return false;
  // A terminal or /dev/null mixes nothing into a file: messages stay where a script expects them.
  if (S_ISCHR(named.st_mode)) return false;
  return out.st_dev == named.st_dev && out.st_ino == named.st_ino;
}

bool messages_off_stdout(const std::vector<std::string>& outputs) {
  for (const std::string& output : outputs)
    if (names_stdout(output)) {
      std::fflush(stdout);
      stdout = stderr;  // NOLINT: glibc documents stdout as an assignable variable
      return true;
    }
  return false;
}

}  // namespace pushpull::app
