// PNG input/output and image comparison (tests, the render command). Thread-safety: pure functions.
#pragma once

#include "pushpull/renderer/types.hpp"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace pushpull::renderer {

// RGBA8 encoded as PNG bytes; throws std::runtime_error for an empty or inconsistent image (`name` in the
// message).
std::vector<uint8_t> encode_png(const TextureRGBA8& image, const std::string& name);
// Writes RGBA8 as PNG straight to `path` (tests and tools: not atomic; the app writes encode_png's bytes
// through a temporary file and rename); throws std::runtime_error naming the file on failure.
void write_png(const std::filesystem::path& path, const TextureRGBA8& image);
// Reads any PNG as RGBA8; throws std::runtime_error naming the file on failure.
TextureRGBA8 read_png(const std::filesystem::path& path);

// Decodes a PNG or JPEG held in memory (e.g. a glTF image) to RGBA8; `name` is used in errors.
TextureRGBA8 decode_image(std::span<const uint8_t> encoded, bool srgb, const std::string& name);

struct ImageComparison {
  bool same_size = false;
  uint32_t differing_pixels = 0;  // pixels whose max channel difference exceeds the tolerance
  uint32_t max_difference = 0;    // 0..255 over all pixels and RGB channels
  double mean_difference = 0.0;   // mean absolute RGB channel difference
  TextureRGBA8 diff;              // |a - b| amplified x4, differing pixels in magenta
};

// Per-pixel comparison of the RGB channels; a pixel differs when a channel differs by > tolerance.
ImageComparison compare_images(const TextureRGBA8& a, const TextureRGBA8& b, uint32_t tolerance);

}  // namespace pushpull::renderer
