// Shared helpers for the assets unit tests: data paths, scratch folders, the glTF validator.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

namespace pushpull::assets::testing {

inline std::filesystem::path shared_data() {
  return std::filesystem::path(PUSHPULL_SHARED_DATA);
}
inline std::filesystem::path gltf_data() {
  return shared_data() / "gltf";
}
inline std::filesystem::path source_dir() {
  return std::filesystem::path(PUSHPULL_SOURCE_DIR);
}

// A fresh folder under the system temp dir, removed at destruction.
class ScratchDir {
 public:
  ScratchDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("pushpull-assets-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// Standard base64 (with padding), for data: URIs in hand-made glTF documents.
inline std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = std::uint32_t{bytes[i]} << 16 |
                            (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

// Appends the bytes of `values` (host order, little-endian on every supported target).
template <typename T>
void append(std::vector<std::uint8_t>& out, std::initializer_list<T> values) {
  for (T v : values) {
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    out.insert(out.end(), bytes, bytes + sizeof(T));
  }
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

struct CommandResult {
  int status = -1;
  std::string output;
};

inline CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int status = ::pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// The Khronos glTF Validator installed by scripts/setup (npm ci in tools/gltf-validator).
// Missing validator is a failure, not a skip: setup installs it.
inline std::filesystem::path validator_script() {
  return source_dir() / "tools/gltf-validator/validate.js";
}

inline ::testing::AssertionResult validates_with_zero_errors(const std::filesystem::path& file) {
  const auto module = source_dir() / "tools/gltf-validator/node_modules/gltf-validator/index.js";
  if (!std::filesystem::exists(module))
    return ::testing::AssertionFailure()
           << "glTF validator missing: run `npm ci --prefix "
           << (source_dir() / "tools/gltf-validator").string() << "` (scripts/setup does)";
  const CommandResult result =
      run_command("node '" + validator_script().string() + "' '" + file.string() + "'");
  if (result.status != 0)
    return ::testing::AssertionFailure() << "validator exit " << result.status << ":\n" << result.output;
  return ::testing::AssertionSuccess() << result.output;
}

}  // namespace pushpull::assets::testing
