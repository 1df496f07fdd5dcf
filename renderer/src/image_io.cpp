#include "pushpull/renderer/image_io.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

// stb (Debian libstb-dev) compiled here: only this file defines the implementations.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
// Static linkage: other modules may compile their own copy of stb.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace pushpull::renderer {

std::vector<uint8_t> encode_png(const TextureRGBA8& image, const std::string& name) {
  if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t{image.width} * image.height * 4)
    throw std::runtime_error(name + ": cannot encode an empty or inconsistent image as PNG");
  std::vector<uint8_t> bytes;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* begin = static_cast<const uint8_t*>(data);
    out->insert(out->end(), begin, begin + size);
  };
  const int ok =
      stbi_write_png_to_func(append, &bytes, static_cast<int>(image.width), static_cast<int>(image.height), 4,
                             image.pixels.data(), static_cast<int>(image.width * 4));
  if (ok == 0) throw std::runtime_error(name + ": cannot encode the image as PNG");
  return bytes;
}

void write_png(const std::filesystem::path& path, const TextureRGBA8& image) {
  if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t{image.width} * image.height * 4)
    throw std::runtime_error(path.string() + ": cannot write an empty or inconsistent image");
  const int ok = stbi_write_png(path.c_str(), static_cast<int>(image.width), static_cast<int>(image.height),
                                4, image.pixels.data(), static_cast<int>(image.width * 4));
  if (ok == 0)
    throw std::runtime_error(path.string() + ": cannot write PNG (directory missing or not writable?)");
}

TextureRGBA8 read_png(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (data == nullptr)
    throw std::runtime_error(path.string() +
                             ": cannot read PNG: " + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
  TextureRGBA8 image;
  image.width = static_cast<uint32_t>(w);
  image.height = static_cast<uint32_t>(h);
  image.pixels.assign(data, data + size_t(w) * size_t(h) * 4);
  stbi_image_free(data);
  return image;
}

TextureRGBA8 decode_image(std::span<const uint8_t> encoded, bool srgb, const std::string& name) {
  int w = 0, h = 0, channels = 0;
  if (encoded.size() > size_t(std::numeric_limits<int>::max()))
    throw std::runtime_error(name + ": image too large to decode");
  unsigned char* data =
      stbi_load_from_memory(encoded.data(), static_cast<int>(encoded.size()), &w, &h, &channels, 4);
  if (data == nullptr)
    throw std::runtime_error(name + ": cannot decode image: " +
                             (stbi_failure_reason() ? stbi_failure_reason() : "unknown reason"));
  TextureRGBA8 image;
  image.width = static_cast<uint32_t>(w);
  image.height = static_cast<uint32_t>(h);
  image.pixels.assign(data, data + size_t(w) * size_t(h) * 4);
  image.srgb = srgb;
  stbi_image_free(data);
  return image;
}

ImageComparison compare_images(const TextureRGBA8& a, const TextureRGBA8& b, uint32_t tolerance) {
  ImageComparison result;
  result.same_size = a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size();
  if (!result.same_size) return result;
  result.diff.width = a.width;
  result.diff.height = a.height;
  result.diff.pixels.resize(a.pixels.size());
  double sum = 0.0;
  for (size_t p = 0; p < a.pixels.size(); p += 4) {
    uint32_t pixel_max = 0;
    for (size_t c = 0; c < 3; ++c) {
      const uint32_t d = static_cast<uint32_t>(std::abs(int(a.pixels[p + c]) - int(b.pixels[p + c])));
      pixel_max = std::max(pixel_max, d);
      sum += d;
      result.diff.pixels[p + c] = static_cast<uint8_t>(std::min<uint32_t>(255, d * 4));
    }
    result.diff.pixels[p + 3] = 255;
    result.max_difference = std::max(result.max_difference, pixel_max);
    if (pixel_max > tolerance) {
      ++result.differing_pixels;
      result.diff.pixels[p] = 255;
      result.diff.pixels[p + 1] = 0;
      result.diff.pixels[p + 2] = 255;
    }
  }
  result.mean_difference = sum / (3.0 * double(a.pixels.size() / 4));
  return result;
}

}  // namespace pushpull::renderer
