#include "pushpull/deform/file_output.hpp"

#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pushpull::deform {
namespace {

namespace fs = std::filesystem;

// The temporaries being written, for the signal handler: a slot is claimed (state 1), its path copied, then
// published (state 2); the handler unlinks published slots only (unlink is async-signal-safe).
struct TemporarySlot {
  std::atomic<int> state{0};
  std::array<char, 4096> path{};
};
std::array<TemporarySlot, 32> g_temporaries;
struct sigaction g_previous_int {
}, g_previous_term{};

// write(2) of a NUL-terminated text (async-signal-safe; no strlen, which POSIX does not list).
void say(const char* text) {
  std::size_t n = 0;
  while (text[n] != '\0') ++n;
  (void)!::write(STDERR_FILENO, text, n);
}

void remove_temporaries_and_end(int signal) {
  for (TemporarySlot& slot : g_temporaries)
    if (slot.state.load() == 2 && ::unlink(slot.path.data()) == 0) {
      say("pushpull: interrupted while writing; removed the unfinished ");
      say(slot.path.data());
      say(" (the file it was to replace is as it was)\n");
    }
  // The signal then does what it would have done: end the process (the default action).
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void on_signal(int signal) {
  const struct sigaction& previous = signal == SIGINT ? g_previous_int : g_previous_term;
  if (previous.sa_handler == SIG_DFL) {
    remove_temporaries_and_end(signal);
  } else if (previous.sa_handler != SIG_IGN) {
    // The program's own handler (a review ends gracefully and finishes its writes): it decides.
    if (previous.sa_flags & SA_SIGINFO)
      previous.sa_sigaction(signal, nullptr, nullptr);
    else
      previous.sa_handler(signal);
  }
}

// Makes on_signal the handler of `signal` unless it is already, remembering the one it replaces.
void ensure_handler(int signal, struct sigaction& previous) {
  struct sigaction current {};
  if (::sigaction(signal, nullptr, &current) != 0) return;
  if (current.sa_handler == &on_signal) return;
  struct sigaction mine {};
  mine.sa_handler = &on_signal;
  sigemptyset(&mine.sa_mask);
  previous = current;
  (void)::sigaction(signal, &mine, nullptr);
}

// Registers a temporary for the signal handler for its lifetime: the handlers are installed and a slot
// claimed first, the temporary's name published before the file is created (so a signal on any thread, at any
// moment, finds every temporary that exists: unlinking a name not created yet fails harmlessly). No
// protection when every slot is taken.
class TemporaryGuard {
 public:
  TemporaryGuard() {
    static std::mutex handlers;  // two first writes at once install the handlers once
    {
      const std::lock_guard lock(handlers);
      ensure_handler(SIGINT, g_previous_int);
      ensure_handler(SIGTERM, g_previous_term);
    }
    for (TemporarySlot& s : g_temporaries) {
      int free = 0;
      if (s.state.compare_exchange_strong(free, 1)) {
        slot_ = &s;
        return;
      }
    }
  }
  // The name the next create will use (too long a name goes unprotected).
  void publish(const std::string& path) {
    if (!slot_) return;
    slot_->state.store(1);
    if (path.size() >= std::tuple_size_v<decltype(TemporarySlot::path)>) return;
    std::memcpy(slot_->path.data(), path.c_str(), path.size() + 1);
    slot_->state.store(2);
  }
  ~TemporaryGuard() {
    if (slot_) slot_->state.store(0);
  }
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;

 private:
  TemporarySlot* slot_ = nullptr;
};

// Six characters for a temporary's name, different on every call and in every process.
std::string random_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t x = (static_cast<std::uint64_t>(::getpid()) << 32) ^ counter.fetch_add(1) ^
                    static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  x ^= x >> 33;  // splitmix64's finaliser: neighbouring inputs give unrelated names
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  static constexpr char kLetters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::string suffix(6, 'a');
  for (char& c : suffix) {
    c = kLetters[x % 62];
    x /= 62;
  }
  return suffix;
}

// The file a path names: a symbolic link's target, its chain followed (up to 40 links, a relative target
// taken from the link's folder); a dangling link gives the file it would create; otherwise the path itself.
fs::path followed(const fs::path& path) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code error;
    if (!fs::is_symlink(fs::symlink_status(p, error))) return p;
    const fs::path target = fs::read_symlink(p, error);
    if (error) return p;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return p;
}

// The descriptor a path names that the process already holds (/dev/stdout, /dev/stderr, /dev/fd/N,
// /proc/self/fd/N): written through as it is, so that a shell's redirection (`>> log`, a pipe) keeps its
// meaning; reopening it would start at the file's beginning or replace the file.
std::optional<int> descriptor_name(const fs::path& path) {
  const std::string p = path.lexically_normal().string();
  if (p == "/dev/stdout") return 1;
  if (p == "/dev/stderr") return 2;
  for (const std::string_view prefix : {std::string_view("/dev/fd/"), std::string_view("/proc/self/fd/")}) {
    if (p.size() <= prefix.size() || p.compare(0, prefix.size(), prefix) != 0) continue;
    int fd = -1;
    const char* first = p.data() + prefix.size();
    const auto [end, error] = std::from_chars(first, p.data() + p.size(), fd);
    if (error == std::errc() && end == p.data() + p.size() && fd >= 0) return fd;
  }
  return std::nullopt;
}

// The same for the path or any link on the way from it (a link `out.json -> /dev/stdout`): followed to the
// end, /dev/stdout leads to the file the shell opened (`>> log`), which a rename would replace.
std::optional<int> inherited_descriptor(const fs::path& path) {
  fs::path p = path;
  std::error_code error;
  // The folder that lists this process's descriptors as the file system names it (/dev/fd and /proc/self/fd
  // are links to /proc/<pid>/fd, which a link may name too).
  const fs::path own_fd = fs::canonical("/proc/self/fd", error);
  for (int hops = 0; hops < 40; ++hops) {
    // Matched as an absolute, normal path: a relative link (../../dev/fd/3) names one too.
    p = fs::absolute(p, error).lexically_normal();
    if (const std::optional<int> fd = descriptor_name(p)) return fd;
    if (!own_fd.empty() && p.has_parent_path()) {
      std::error_code canonical_error;
      const fs::path folder = fs::canonical(p.parent_path(), canonical_error);
      if (!canonical_error && folder == own_fd) {
        if (const std::optional<int> fd = descriptor_name(fs::path("/dev/fd") / p.filename())) return fd;
      }
    }
    if (!fs::is_symlink(fs::symlink_status(p, error))) return std::nullopt;
    const fs::path target = fs::read_symlink(p, error);
    if (error) return std::nullopt;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return std::nullopt;
}

std::string mode_text(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", unsigned(mode & 07777));
  return text;
}

// Writes all of `bytes` to `fd`; returns errno, 0 on success.
int write_all(int fd, std::string_view bytes) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    written += static_cast<std::size_t>(n);
  }
  return 0;
}

// Returns the problem ("" on success).
std::string write_to(const fs::path& requested, std::string_view bytes) {
  if (requested.empty()) return "an empty file name";
  if (const std::optional<int> fd = inherited_descriptor(requested)) {
    if (::fcntl(*fd, F_GETFD) == -1) return "no such open file descriptor";
    const int failed = write_all(*fd, bytes);
    return failed ? std::string("write failed: ") + std::strerror(failed) : std::string();
  }
  const fs::path path = followed(requested);
  struct stat existing {};
  const bool exists = ::stat(path.c_str(), &existing) == 0;
  if (exists && S_ISDIR(existing.st_mode)) return "is a folder, not a file";
  if (exists && !S_ISREG(existing.st_mode)) {  // a device, FIFO or socket: written in place
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return std::string("cannot open it for writing: ") + std::strerror(errno);
    const int failed = write_all(fd, bytes);
    ::close(fd);
    return failed ? std::string("write failed: ") + std::strerror(failed) : std::string();
  }
  if (exists && (existing.st_mode & 0222) == 0)
    return "is read-only (mode " + mode_text(existing.st_mode) + "); not overwritten";
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::string temp_leaf = ".";  // (built in steps: GCC 12 warns falsely on a + b + c here)
  temp_leaf += path.filename().string();
  temp_leaf += ".tmp-";
  const std::string temp_prefix = (folder / temp_leaf).string();
  // The name is published for the signal handler before the file exists (TemporaryGuard), then created
  // exclusively: mkstemp would create first and leave a moment in which a signal on another thread (a review
  // has several) ends the process with the temporary unknown to the handler.
  TemporaryGuard guard;
  std::string temp_name;
  int fd = -1;
  int create_error = 0;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp_name = temp_prefix + random_suffix();
    guard.publish(temp_name);
    fd = ::open(temp_name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    create_error = errno;
    if (fd < 0 && create_error != EEXIST) break;
  }
  if (fd < 0)
    return "cannot create a temporary file in " + folder.string() + ": " + std::strerror(create_error);
  auto give_up = [&](const char* what, int error) {
    ::close(fd);
    ::unlink(temp_name.c_str());
    return std::string(what) + ": " + std::strerror(error);
  };
  if (const int failed = write_all(fd, bytes)) return give_up("write failed", failed);
  // The temporary is created 0600: a new result is an ordinary file others may read (umask is not
  // consulted: reading it means changing it, which races with other threads); a replaced one keeps its mode.
  if (::fchmod(fd, exists ? (existing.st_mode & 07777) : 0644) != 0) return give_up("chmod failed", errno);
  if (::fsync(fd) != 0) return give_up("fsync failed", errno);
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(temp_name.c_str());
    return std::string("close failed: ") + std::strerror(saved);
  }
  if (::rename(temp_name.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(temp_name.c_str());
    return std::string("cannot rename the temporary file into place: ") + std::strerror(saved);
  }
  return {};
}

}  // namespace

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  const std::string problem = write_to(path, bytes);
  if (!problem.empty()) throw std::runtime_error(path.string() + ": " + problem);
}

std::string output_path_problem(const fs::path& requested, MissingFolder missing, OutputWrite write) {
  if (requested.empty()) return "an empty file name";
  if (const std::optional<int> fd = inherited_descriptor(requested))
    return ::fcntl(*fd, F_GETFD) == -1 ? "names descriptor " + std::to_string(*fd) + ", which is not open"
                                       : std::string();
  const fs::path path = followed(requested);
  // The file is written as a temporary in its folder renamed over it: the folder (or, where it will be made,
  // the nearest one that exists) must take new files. Said now, not after the work that makes the file.
  auto unwritable = [](const fs::path& folder) -> std::string {
    const fs::path named = folder.empty() ? fs::path(".") : folder;
    if (::access(named.c_str(), W_OK | X_OK) == 0) return {};
    return "the folder " + named.string() + " does not take new files (" + std::strerror(errno) + ")";
  };
  struct stat existing {};
  if (::stat(path.c_str(), &existing) == 0) {
    if (S_ISDIR(existing.st_mode)) return "is a folder, not a file";
    if (S_ISREG(existing.st_mode) && (existing.st_mode & 0222) == 0)
      return "is read-only (mode " + mode_text(existing.st_mode) + "); not overwritten";
    if (S_ISREG(existing.st_mode) && write == OutputWrite::Atomic) return unwritable(path.parent_path());
    return {};
  }
  fs::path folder = path.parent_path();
  std::error_code error;
  if (!folder.empty() && !fs::is_directory(folder, error)) {
    if (fs::exists(folder, error)) return folder.string() + " is a file, not a folder";
    if (missing != MissingFolder::WillBeMade) return "the folder " + folder.string() + " does not exist";
    while (!folder.empty() && folder != folder.parent_path() && !fs::exists(folder, error))
      folder = folder.parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder, error)) return {};  // a file up the path: making the folder says so
  }
  return unwritable(folder);
}

bool holds_descriptor(const fs::path& path) {
  return inherited_descriptor(path).has_value();
}

bool same_output_file(const fs::path& a, const fs::path& b) {
  // The descriptors a shell hands over are streams: two results may go to one (both to stdout).
  if (inherited_descriptor(a) || inherited_descriptor(b)) return false;
  std::error_code error_a, error_b;
  const fs::path ca = fs::weakly_canonical(fs::absolute(followed(a), error_a), error_a);
  const fs::path cb = fs::weakly_canonical(fs::absolute(followed(b), error_b), error_b);
  if (error_a || error_b) return followed(a).lexically_normal() == followed(b).lexically_normal();
  return ca == cb;
}

}  // namespace pushpull::deform
