// A command whose output file is the process's standard output (`--metrics /dev/stdout`, `--out
// /dev/fd/1`, or the file stdout is redirected to) would interleave its progress and summary lines with
// the file's bytes: a JSON followed by "wrote ...", a PNG with text after its end. Such a command sends its
// messages to stderr instead.
// Thread-safety: call before the command prints or starts threads (it replaces the C stream `stdout`).
#pragma once

#include <string>
#include <vector>

namespace pushpull::app {

// Whether `path` is the file or pipe the process's standard output is (same device and inode; a terminal or
// other character device, /dev/null, is not counted: nothing there is a file the messages would spoil).
[[nodiscard]] bool names_stdout(const std::string& path);

// Points the C stream `stdout` at stderr when one of `outputs` names the standard output (the GNU C
// library's `stdout` is a variable that may be assigned). Returns whether it did.
bool messages_off_stdout(const std::vector<std::string>& outputs);

}  // namespace pushpull::app
