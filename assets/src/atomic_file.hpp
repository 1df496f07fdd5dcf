// Atomic file replacement: write a temporary file in the target's folder, flush it to disk, rename
// it over the target. A crash or error at any point leaves the previous target intact.
// Thread-safety: reentrant (distinct temporary names). Throws AssetError.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace pushpull::assets::detail {

void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace pushpull::assets::detail
