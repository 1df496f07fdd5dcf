#include "image_header.hpp"

#include <cstring>

namespace pushpull::assets::detail {

namespace {

std::uint32_t big_endian(std::span<const std::uint8_t> b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = v << 8 | b[at + static_cast<std::size_t>(i)];
  return v;
}

void jpeg_size(std::span<const std::uint8_t> b, ImageHeader& header) {
  std::size_t at = 2;
  while (at + 9 < b.size()) {
    if (b[at] != 0xFF) return;
    const std::uint8_t marker = b[at + 1];
    if (marker == 0xFF) {
      ++at;
      continue;
    }
    const std::uint32_t length = big_endian(b, at + 2, 2);
    const bool start_of_frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (start_of_frame) {
      header.height = static_cast<int>(big_endian(b, at + 5, 2));
      header.width = static_cast<int>(big_endian(b, at + 7, 2));
      return;
    }
    if (length < 2) return;
    at += 2 + length;
  }
}

}  // namespace

ImageHeader read_image_header(std::span<const std::uint8_t> b) {
  ImageHeader header;
  static const std::uint8_t png[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() >= 24 && std::memcmp(b.data(), png, 8) == 0) {
    header.mime_type = "image/png";
    if (std::memcmp(b.data() + 12, "IHDR", 4) == 0) {
      header.width = static_cast<int>(big_endian(b, 16, 4) & 0x7FFFFFFF);
      header.height = static_cast<int>(big_endian(b, 20, 4) & 0x7FFFFFFF);
    }
  } else if (b.size() >= 4 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) {
    header.mime_type = "image/jpeg";
    jpeg_size(b, header);
  } else if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
             std::memcmp(b.data() + 8, "WEBP", 4) == 0) {
    header.mime_type = "image/webp";
  } else if (b.size() >= 12 && b[0] == 0xAB && b[1] == 'K' && b[2] == 'T' && b[3] == 'X' && b[5] == '2' &&
             b[6] == '0') {
    header.mime_type = "image/ktx2";
  }
  return header;
}

}  // namespace pushpull::assets::detail
