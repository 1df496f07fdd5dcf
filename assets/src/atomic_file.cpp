#include "atomic_file.hpp"

#include "pushpull/assets/error.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pushpull::assets::detail {

void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  const std::filesystem::path folder =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  std::string leaf = path.filename().string();
  leaf.insert(0, 1, '.');
  leaf.append(".tmp-XXXXXX");
  const std::string pattern = (folder / leaf).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw AssetError(path.string() + ": cannot create a temporary file: " + std::strerror(errno));
  auto fail = [&](const std::string& what) {
    const int saved = errno;
    ::close(fd);
    ::unlink(name.data());
    throw AssetError(path.string() + ": " + what + ": " + std::strerror(saved));
  };
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write failed");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fchmod(fd, 0644) != 0) fail("chmod failed");
  if (::fsync(fd) != 0) fail("fsync failed");
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(name.data());
    throw AssetError(path.string() + ": close failed: " + std::strerror(saved));
  }
  if (::rename(name.data(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(name.data());
    throw AssetError(path.string() + ": rename failed: " + std::strerror(saved));
  }
}

}  // namespace pushpull::assets::detail
