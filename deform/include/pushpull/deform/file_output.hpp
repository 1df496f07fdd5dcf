// Writing a result file without losing the user's data: atomically where the target is (or will be) a
// regular file, through a symbolic link to the file it names, and straight into a stream the user named
// (/dev/stdout, a FIFO), which cannot be replaced.
//
// - A regular file is written to a temporary file in its folder (".NAME.tmp-XXXXXX"), flushed and renamed
//   over it, so a reader sees the old file or the new one, never half of one; an existing file keeps its
//   permissions. A file without any write permission is refused, not replaced.
// - A symbolic link is followed (a chain too, and a link to a file not there yet): the file it names is
//   replaced the same way, the link stays.
// - A descriptor the process holds (/dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N), named or reached
//   through links, is written through as it is, so a shell's `> file`, `>> log` or pipe keeps its meaning.
// - A character device, FIFO or socket is opened and written in place (no temporary).
// - SIGINT or SIGTERM while a temporary exists removes it before the process ends (where the signal would
//   end the process; a handler the program installed, e.g. a review's graceful Ctrl-C, is called instead).
//
// Thread-safety: both functions may be called from several threads at once (up to 32 writes in flight are
// cleaned up on a signal; more still write correctly).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace pushpull::deform {

// Writes `bytes` to `path` as above. Throws std::runtime_error naming the file and the problem (the system
// error, or why it is refused); the temporary is removed.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// What a command does about an output's folder that is not there yet.
enum class MissingFolder { Refused, WillBeMade };
// How an output is written: Atomic (write_file_atomically: a temporary in its folder renamed over it, so the
// folder must take new files) or InPlace (opened and written as it is, as a log: an existing file only needs
// its own write permission).
enum class OutputWrite { Atomic, InPlace };

// Why `path` cannot be written as above, or "" when it can (as far as one can tell before writing): its
// name is empty, its folder does not exist (unless it will be made) or is a file, it is a folder, it has no
// write permission, its folder (or the nearest existing one above a folder to be made) takes no new files.
// For checking every output of a command before writing any of them.
[[nodiscard]] std::string output_path_problem(const std::filesystem::path& path,
                                              MissingFolder missing = MissingFolder::Refused,
                                              OutputWrite write = OutputWrite::Atomic);

// Whether `path`, or a link on the way from it, names a descriptor the process holds (written through).
[[nodiscard]] bool holds_descriptor(const std::filesystem::path& path);

// Whether two output paths name the same file (after following symbolic links; either may not exist yet).
[[nodiscard]] bool same_output_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace pushpull::deform
