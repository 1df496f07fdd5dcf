// Image type and size from the first bytes of an encoded image, without decoding it.
// Thread-safety: pure function (no global state, unlike stb_image's stbi_info).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace pushpull::assets::detail {

struct ImageHeader {
  std::string mime_type;  // "image/png", "image/jpeg", "image/webp", "image/ktx2", or empty
  int width = 0;          // 0 when the header does not say (or is not understood)
  int height = 0;
};

ImageHeader read_image_header(std::span<const std::uint8_t> bytes);

}  // namespace pushpull::assets::detail
