// Private: the PLY header (format, elements and their properties), read once for the reader (mesh_io_ply.cpp)
// and for the in-place rewrite of vertex positions (mesh_io_rewrite.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pushpull::deform::detail {

enum class Encoding { ascii, binary_le, binary_be };
enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

inline bool scalar_type_from_name(std::string_view name, ScalarType& type) {
  struct Entry {
    std::string_view name;
    ScalarType type;
  };
  static constexpr Entry entries[] = {
      {"char", ScalarType::int8},      {"int8", ScalarType::int8},       {"uchar", ScalarType::uint8},
      {"uint8", ScalarType::uint8},    {"short", ScalarType::int16},     {"int16", ScalarType::int16},
      {"ushort", ScalarType::uint16},  {"uint16", ScalarType::uint16},   {"int", ScalarType::int32},
      {"int32", ScalarType::int32},    {"uint", ScalarType::uint32},     {"uint32", ScalarType::uint32},
      {"float", ScalarType::float32},  {"float32", ScalarType::float32}, {"double", ScalarType::float64},
      {"float64", ScalarType::float64}};
  for (const Entry& entry : entries) {
    if (entry.name == name) {
      type = entry.type;
      return true;
    }
  }
  return false;
}

inline std::size_t scalar_size(ScalarType type) {
  switch (type) {
    case ScalarType::int8:
    case ScalarType::uint8:
      return 1;
    case ScalarType::int16:
    case ScalarType::uint16:
      return 2;
    case ScalarType::int32:
    case ScalarType::uint32:
    case ScalarType::float32:
      return 4;
    case ScalarType::float64:
      return 8;
  }
  return 8;
}

struct Property {
  std::string name;
  ScalarType type = ScalarType::float32;
  bool is_list = false;
  ScalarType count_type = ScalarType::uint8;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::size_t header_line = 0;
  std::vector<Property> properties;
};

struct PlyHeader {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;  // in file order
  std::size_t body_offset = 0;    // the first byte after end_header's line
  std::size_t body_line = 0;      // the 1-based line number there (ASCII)
};

// Reads the header of `contents`. Throws MeshIoError naming `name` and the line: no 'ply' magic, an unknown
// format, a malformed element or property line, a property before any element, no end_header, no format.
[[nodiscard]] PlyHeader read_ply_header(std::string_view contents, const std::string& name);

}  // namespace pushpull::deform::detail
