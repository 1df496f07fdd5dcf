// SHA-256 (FIPS 180-4) of bytes and of files: a recording names the model it was made on by the digest of
// the model file, and a replay refuses another file. Written here because the project has no crypto
// dependency; not constant-time (it hashes public files, no secrets).
// Thread-safety: Sha256 is a value for one thread; the free functions have no state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace pushpull::app {

class Sha256 {
 public:
  Sha256();
  void update(std::span<const std::uint8_t> bytes);
  // The 32-byte digest; the object must not be updated afterwards.
  [[nodiscard]] std::array<std::uint8_t, 32> finish();

 private:
  void block(const std::uint8_t* p);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

// Lowercase hex digest of `bytes`.
[[nodiscard]] std::string sha256_hex(std::span<const std::uint8_t> bytes);
[[nodiscard]] std::string sha256_hex(const std::string& text);
// Lowercase hex digest of a file's bytes. Throws std::runtime_error naming the file when it cannot be read.
[[nodiscard]] std::string sha256_file_hex(const std::string& path);

}  // namespace pushpull::app
