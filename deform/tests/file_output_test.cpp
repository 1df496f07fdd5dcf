// deform/file_output: results replace regular files atomically and keep their mode, follow symbolic links,
// go straight into streams (FIFOs), refuse read-only files and folders, and leave no temporary behind when
// the process is interrupted mid-write.
#include "pushpull/deform/file_output.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <csignal>

namespace {

namespace fs = std::filesystem;
namespace pd = pushpull::deform;

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("pushpull_file_output_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int entries(const fs::path& folder) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++n;
  return n;
}

mode_t mode_of(const fs::path& path) {
  struct stat s {};
  EXPECT_EQ(::stat(path.c_str(), &s), 0);
  return s.st_mode & 07777;
}

TEST(FileOutput, AReplacedFileKeepsItsModeAndANewOneIsReadableByOthers) {
  TempDir dir;
  const fs::path kept = dir.path / "kept.json", fresh = dir.path / "fresh.json";
  { std::ofstream(kept) << "old"; }
  ASSERT_EQ(::chmod(kept.c_str(), 0640), 0);
  pd::write_file_atomically(kept, "new");
  pd::write_file_atomically(fresh, "new");
  EXPECT_EQ(read_all(kept), "new");
  EXPECT_EQ(mode_of(kept), 0640u);
  EXPECT_EQ(mode_of(fresh), 0644u);
  EXPECT_EQ(entries(dir.path), 2);  // no temporary left
}

TEST(FileOutput, ASymbolicLinkIsFollowedAndStays) {
  TempDir dir;
  fs::create_directories(dir.path / "real");
  const fs::path target = dir.path / "real" / "metrics.json", link = dir.path / "link.json";
  { std::ofstream(target) << "old"; }
  fs::create_symlink(fs::path("real") / "metrics.json", link);  // relative, as ln -s makes them
  pd::write_file_atomically(link, "new");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(read_all(target), "new");
  EXPECT_TRUE(pd::same_output_file(link, target));
  EXPECT_FALSE(pd::same_output_file(link, dir.path / "other.json"));
}

// A link to a file not there yet (and a chain of links) names that file: it is created, the links stay, and
// two outputs reaching one file through links are the same output.
TEST(FileOutput, ALinkToAFileNotThereYetCreatesThatFile) {
  TempDir dir;
  const fs::path target = dir.path / "model.off", link = dir.path / "link.off",
                 chain = dir.path / "chain.off";
  fs::create_symlink("model.off", link);
  fs::create_symlink("link.off", chain);
  EXPECT_TRUE(pd::same_output_file(chain, target));
  EXPECT_TRUE(pd::same_output_file(link, chain));
  pd::write_file_atomically(chain, "new");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(chain)));
  EXPECT_EQ(read_all(target), "new");
}

// A descriptor the process holds (a shell's `>> log` on stdout) is written through as it is: appended to, not
// replaced.
TEST(FileOutput, ADescriptorItHoldsIsWrittenThrough) {
  TempDir dir;
  const fs::path log = dir.path / "log.txt";
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "earlier\n", 8), 8);
  pd::write_file_atomically("/dev/fd/" + std::to_string(fd), "{\"metrics\": 1}\n");
  pd::write_file_atomically("/proc/self/fd/" + std::to_string(fd), "more\n");
  ::close(fd);
  EXPECT_EQ(read_all(log), "earlier\n{\"metrics\": 1}\nmore\n");
  EXPECT_EQ(entries(dir.path), 1);
  EXPECT_FALSE(pd::same_output_file("/dev/stdout", "/dev/stdout"));  // streams: both results may go there
}

// So is one reached through a link (out.json -> /dev/fd/N): followed to its end, the link leads to the log
// itself, which a temporary renamed over it would replace.
TEST(FileOutput, ALinkToADescriptorItHoldsIsWrittenThrough) {
  TempDir dir;
  const fs::path log = dir.path / "log.txt";
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "earlier\n", 8), 8);
  const fs::path link = dir.path / "out.json";
  fs::create_symlink("/dev/fd/" + std::to_string(fd), link);
  EXPECT_TRUE(pd::holds_descriptor(link));
  EXPECT_EQ(pd::output_path_problem(link), "");
  pd::write_file_atomically(link, "{\"metrics\": 1}\n");
  ::close(fd);
  EXPECT_EQ(read_all(log), "earlier\n{\"metrics\": 1}\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_FALSE(pd::holds_descriptor(log));
  EXPECT_EQ(pd::output_path_problem(""), "an empty file name");
  // A relative link (../../dev/fd/N from a folder) names it too, and one to a descriptor not open is refused
  // before anything is written.
  const int again = ::open(log.c_str(), O_WRONLY | O_APPEND);
  ASSERT_GE(again, 0);
  fs::path up;
  for (const auto& part : fs::absolute(dir.path)) {
    if (part != "/" && !part.empty()) up /= "..";
  }
  const fs::path relative = dir.path / "relative.json";
  fs::create_symlink(up / "dev" / "fd" / std::to_string(again), relative);
  EXPECT_TRUE(pd::holds_descriptor(relative)) << fs::read_symlink(relative);
  pd::write_file_atomically(relative, "relative\n");
  ::close(again);
  EXPECT_EQ(read_all(log), "earlier\n{\"metrics\": 1}\nrelative\n");
  const fs::path closed = dir.path / "closed.json";
  fs::create_symlink("/dev/fd/987", closed);
  EXPECT_EQ(pd::output_path_problem(closed), "names descriptor 987, which is not open");
}

TEST(FileOutput, AFifoIsWrittenInPlace) {
  TempDir dir;
  const fs::path fifo = dir.path / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_all(fifo); });
  pd::write_file_atomically(fifo, "through the pipe");
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  struct stat s {};
  ASSERT_EQ(::lstat(fifo.c_str(), &s), 0);
  EXPECT_TRUE(S_ISFIFO(s.st_mode));
}

TEST(FileOutput, AReadOnlyFileAndAFolderAreRefusedAndLeftAlone) {
  TempDir dir;
  const fs::path read_only = dir.path / "ro.off";
  { std::ofstream(read_only) << "old"; }
  ASSERT_EQ(::chmod(read_only.c_str(), 0444), 0);
  for (const fs::path& path : {read_only, dir.path}) {
    try {
      pd::write_file_atomically(path, "new");
      FAIL() << path << ": no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path == read_only ? "read-only (mode 0444)" : "is a folder"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(read_all(read_only), "old");
  EXPECT_EQ(mode_of(read_only), 0444u);
  EXPECT_EQ(entries(dir.path), 1);
  EXPECT_NE(pd::output_path_problem(read_only).find("read-only"), std::string::npos);
  EXPECT_NE(pd::output_path_problem(dir.path).find("is a folder"), std::string::npos);
  EXPECT_NE(pd::output_path_problem(dir.path / "missing" / "out.off").find("does not exist"),
            std::string::npos);
  EXPECT_EQ(pd::output_path_problem(dir.path / "new.off"), "");
  EXPECT_NE(pd::output_path_problem(read_only / "m.json").find("ro.off is a file, not a folder"),
            std::string::npos);
  // A folder that takes no new files (read-only to this user, or on a read-only file system: /proc/sys even
  // for root) is said before the work whose result would be lost at the end; also where the folder will be
  // made inside it.
  if (::access("/proc/sys", W_OK) != 0) {
    EXPECT_NE(
        pd::output_path_problem("/proc/sys/out.glb").find("the folder /proc/sys does not take new files"),
        std::string::npos)
        << pd::output_path_problem("/proc/sys/out.glb");
    EXPECT_NE(pd::output_path_problem("/proc/sys/a/b/out.glb", pd::MissingFolder::WillBeMade)
                  .find("the folder /proc/sys does not take new files"),
              std::string::npos);
  }
  if (::geteuid() != 0) {  // root writes into a mode-0555 folder
    const fs::path locked = dir.path / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_NE(pd::output_path_problem(locked / "out.off").find("does not take new files"), std::string::npos);
    fs::permissions(locked, fs::perms::owner_all);
  }
}

// A child process interrupted (SIGINT, default action) while it writes a large file: it ends by the signal,
// and neither the temporary nor the target is left.
TEST(FileOutput, AnInterruptedWriteLeavesNoTemporary) {
  TempDir dir;
  const fs::path target = dir.path / "big.json";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGINT, SIG_DFL);
    const std::string big(std::size_t{1} << 28, 'x');  // 256 MiB: long enough to interrupt
    try {
      pd::write_file_atomically(target, big);
    } catch (...) {
    }
    ::_exit(0);
  }
  bool seen = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    for (const auto& e : fs::directory_iterator(dir.path))
      if (e.path().filename().string().rfind(".big.json.tmp-", 0) == 0) seen = true;
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (!seen) {
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    GTEST_SKIP() << "the child never showed its temporary (too fast or too slow to start)";
  }
  ::kill(child, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  if (WIFEXITED(status)) GTEST_SKIP() << "the write finished before the signal came";
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  // No temporary is left. The target is either absent (interrupted before the rename) or whole (the signal
  // came between the rename and the child's exit, on a slow run: 1 of 299 under the sanitizers once).
  for (const auto& e : fs::directory_iterator(dir.path)) {
    EXPECT_EQ(e.path(), target) << "a temporary was left";
    if (e.path() == target) {
      EXPECT_EQ(fs::file_size(target), std::uintmax_t{1} << 28) << "a partial target";
    }
  }
}

}  // namespace
