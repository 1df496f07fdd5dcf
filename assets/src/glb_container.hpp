// The GLB container (glTF 2.0 binary): 12-byte header, a JSON chunk, an optional BIN chunk.
// parse_glb checks every length against the data before use; write_glb_container pads chunks
// to 4 bytes as the specification requires. Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pushpull::assets::detail {

struct GlbChunks {
  std::string_view json;              // views into the parsed bytes
  std::span<const std::uint8_t> bin;  // empty when there is no BIN chunk
};

bool looks_like_glb(std::span<const std::uint8_t> bytes);

// Throws AssetError (prefixed with `name`) on a truncated or inconsistent container.
GlbChunks parse_glb(std::span<const std::uint8_t> bytes, const std::string& name);

std::vector<std::uint8_t> write_glb_container(std::string_view json, std::span<const std::uint8_t> bin);

}  // namespace pushpull::assets::detail
