#include "glb_container.hpp"

#include "pushpull/assets/error.hpp"

#include <cstring>
#include <optional>

namespace pushpull::assets::detail {

namespace {

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

std::uint32_t read_u32(std::span<const std::uint8_t> bytes, std::size_t offset) {
  return std::uint32_t{bytes[offset]} | std::uint32_t{bytes[offset + 1]} << 8 |
         std::uint32_t{bytes[offset + 2]} << 16 | std::uint32_t{bytes[offset + 3]} << 24;
}

void append_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace

bool looks_like_glb(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 4 && read_u32(bytes, 0) == kMagic;
}

// Where the chunks as declared by their own length fields end (JSON, then an optional BIN chunk), read
// only from bytes that exist; lets a too-short file (truncated) be told from a corrupt length field.
// nullopt when the file ends before the BIN chunk's header could be read.
std::optional<std::uint64_t> declared_end(std::span<const std::uint8_t> bytes, std::uint64_t json_length) {
  const std::uint64_t json_end = 20 + json_length;
  const std::uint64_t bin_header = (json_end + 3) & ~std::uint64_t{3};
  if (bin_header >= bytes.size()) return json_end;  // nothing after the JSON chunk
  if (bin_header + 8 > bytes.size()) return std::nullopt;
  if (read_u32(bytes, bin_header + 4) != kChunkBin) return json_end;
  return bin_header + 8 + read_u32(bytes, bin_header);
}

GlbChunks parse_glb(std::span<const std::uint8_t> bytes, const std::string& name) {
  auto fail = [&](const std::string& what) { throw AssetError(name + ": invalid GLB: " + what); };
  if (bytes.size() < 20)
    fail("truncated header (" + std::to_string(bytes.size()) +
         " bytes; a GLB begins with a 12-byte header and its JSON chunk's 8-byte header)");
  if (read_u32(bytes, 0) != kMagic) fail("bad magic");
  if (read_u32(bytes, 4) != 2)
    fail("version " + std::to_string(read_u32(bytes, 4)) + " (only 2 is supported)");
  const std::uint64_t total = read_u32(bytes, 8);
  const std::uint64_t size = bytes.size();
  const std::uint64_t json_length = read_u32(bytes, 12);
  if (total > size) {
    const std::optional<std::uint64_t> chunks_end = declared_end(bytes, json_length);
    if (chunks_end && *chunks_end <= size && ((*chunks_end + 3) & ~std::uint64_t{3}) >= size)
      fail("corrupt header: its length field says " + std::to_string(total) + " bytes, but the file has " +
           std::to_string(size) +
           " and its chunks end there (a corrupt length field, or a file cut exactly after a chunk)");
    if (!chunks_end || *chunks_end > size)
      fail("truncated: the header says " + std::to_string(total) + " bytes, the file ends after " +
           std::to_string(size) + ", inside a chunk");
    fail("corrupt length fields: the header says " + std::to_string(total) +
         " bytes, the chunks end at byte " + std::to_string(*chunks_end) + ", the file has " +
         std::to_string(size));
  }
  if (read_u32(bytes, 16) != kChunkJson) fail("first chunk is not JSON");
  if (20 + json_length > total)
    fail("corrupt JSON chunk header: its length field says " + std::to_string(json_length) + " bytes, only " +
         std::to_string(total - 20) + " follow it");
  GlbChunks chunks;
  chunks.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20, json_length);
  std::uint64_t offset = 20 + json_length;
  offset = (offset + 3) & ~std::uint64_t{3};
  if (offset + 8 <= total) {
    const std::uint64_t bin_length = read_u32(bytes, offset);
    const std::uint32_t type = read_u32(bytes, offset + 4);
    if (type == kChunkBin) {
      if (offset + 8 + bin_length > total)
        fail("corrupt BIN chunk header: its length field says " + std::to_string(bin_length) +
             " bytes, only " + std::to_string(total - offset - 8) + " follow it");
      chunks.bin = bytes.subspan(offset + 8, bin_length);
    }
  }
  return chunks;
}

std::vector<std::uint8_t> write_glb_container(std::string_view json, std::span<const std::uint8_t> bin) {
  const std::size_t json_padded = (json.size() + 3) & ~std::size_t{3};
  const std::size_t bin_padded = (bin.size() + 3) & ~std::size_t{3};
  const std::size_t total = 12 + 8 + json_padded + (bin.empty() ? 0 : 8 + bin_padded);
  if (total > 0xFFFFFFFFu) throw AssetError("GLB would exceed 4 GiB");
  std::vector<std::uint8_t> out;
  out.reserve(total);
  append_u32(out, kMagic);
  append_u32(out, 2);
  append_u32(out, static_cast<std::uint32_t>(total));
  append_u32(out, static_cast<std::uint32_t>(json_padded));
  append_u32(out, kChunkJson);
  out.insert(out.end(), json.begin(), json.end());
  out.resize(out.size() + json_padded - json.size(), ' ');
  if (!bin.empty()) {
    append_u32(out, static_cast<std::uint32_t>(bin_padded));
    append_u32(out, kChunkBin);
    out.insert(out.end(), bin.begin(), bin.end());
    out.resize(out.size() + bin_padded - bin.size(), 0);
  }
  return out;
}

}  // namespace pushpull::assets::detail
