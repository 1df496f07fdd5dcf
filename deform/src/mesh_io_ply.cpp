// PLY reader: ASCII, binary little-endian and binary big-endian.
#include "mesh_io_detail.hpp"
#include "text_scan.hpp"

#include <bit>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::deform {

using detail::fail;

namespace {

enum class Encoding { ascii, binary_le, binary_be };
enum class ScalarType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool scalar_type_from_name(std::string_view name, ScalarType& type) {
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

std::size_t scalar_size(ScalarType type) {
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

// Reads the values of the body, in ASCII (whitespace-separated, across lines) or binary.
class BodyReader {
 public:
  BodyReader(std::string_view body, Encoding encoding, std::size_t first_line, const std::string& name)
      : body_(body), encoding_(encoding), line_(first_line), name_(name) {}

  double read(ScalarType type) {
    if (encoding_ == Encoding::ascii) return read_ascii(type);
    const std::size_t size = scalar_size(type);
    if (body_.size() - pos_ < size)
      fail(name_, 0, "truncated: binary data ends early (offset " + std::to_string(pos_) + ")");
    unsigned char bytes[8];
    std::memcpy(bytes, body_.data() + pos_, size);
    pos_ += size;
    const bool file_is_little = encoding_ == Encoding::binary_le;
    if (file_is_little != (std::endian::native == std::endian::little)) {
      for (std::size_t i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    }
    switch (type) {
      case ScalarType::int8:
        return static_cast<double>(static_cast<std::int8_t>(bytes[0]));
      case ScalarType::uint8:
        return static_cast<double>(bytes[0]);
      case ScalarType::int16:
        return decode<std::int16_t>(bytes);
      case ScalarType::uint16:
        return decode<std::uint16_t>(bytes);
      case ScalarType::int32:
        return decode<std::int32_t>(bytes);
      case ScalarType::uint32:
        return decode<std::uint32_t>(bytes);
      case ScalarType::float32:
        return decode<float>(bytes);
      case ScalarType::float64:
        return decode<double>(bytes);
    }
    return 0.0;
  }

  [[nodiscard]] std::size_t line() const { return encoding_ == Encoding::ascii ? line_ : 0; }
  [[nodiscard]] std::size_t bytes_left() const { return body_.size() - pos_; }

 private:
  template <typename T>
  static double decode(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }

  double read_ascii(ScalarType type) {
    while (pos_ < body_.size() && (detail::is_space(body_[pos_]) || body_[pos_] == '\n')) {
      if (body_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= body_.size()) fail(name_, line_, "truncated: the data ends before every element was read");
    const std::size_t start = pos_;
    while (pos_ < body_.size() && !detail::is_space(body_[pos_]) && body_[pos_] != '\n') ++pos_;
    const std::string_view token = body_.substr(start, pos_ - start);
    double value = 0.0;
    if (!detail::parse_double(token, value))
      fail(name_, line_, "'" + std::string(token) + "' is not a number");
    if (type != ScalarType::float32 && type != ScalarType::float64 &&
        value != static_cast<double>(static_cast<std::int64_t>(value))) {
      fail(name_, line_, "'" + std::string(token) + "' is not an integer");
    }
    return value;
  }

  std::string_view body_;
  Encoding encoding_;
  std::size_t pos_ = 0;
  std::size_t line_;
  const std::string& name_;
};

}  // namespace

Mesh parse_ply(std::string_view contents, const std::string& name) {
  detail::LineCursor cursor(contents);
  std::string_view line;
  if (!cursor.next(line) || detail::strip_comment(line, '\0') != "ply")
    fail(name, 1, "not a PLY file (no 'ply' magic)");

  Encoding encoding = Encoding::ascii;
  bool have_format = false;
  std::vector<Element> elements;
  bool ended = false;
  while (cursor.next(line)) {
    detail::Tokens tokens(line);
    std::string_view keyword;
    if (!tokens.next(keyword) || keyword == "comment" || keyword == "obj_info") continue;
    std::string_view a, b, c, d;
    if (keyword == "end_header") {
      ended = true;
      break;
    }
    if (keyword == "format") {
      tokens.next(a);
      if (a == "ascii")
        encoding = Encoding::ascii;
      else if (a == "binary_little_endian")
        encoding = Encoding::binary_le;
      else if (a == "binary_big_endian")
        encoding = Encoding::binary_be;
      else
        fail(name, cursor.line_number(), "unknown PLY format '" + std::string(a) + "'");
      have_format = true;
    } else if (keyword == "element") {
      Element element;
      std::int64_t count = -1;
      if (!tokens.next(a) || !tokens.next(b) || !detail::parse_int64(b, count) || count < 0) {
        fail(name, cursor.line_number(), "malformed element line");
      }
      element.name = std::string(a);
      element.count = count;
      element.header_line = cursor.line_number();
      elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (elements.empty()) fail(name, cursor.line_number(), "property before any element");
      Property property;
      tokens.next(a);
      if (a == "list") {
        property.is_list = true;
        if (!tokens.next(b) || !tokens.next(c) || !tokens.next(d) ||
            !scalar_type_from_name(b, property.count_type) || !scalar_type_from_name(c, property.type)) {
          fail(name, cursor.line_number(), "malformed list property");
        }
        property.name = std::string(d);
      } else {
        if (!scalar_type_from_name(a, property.type) || !tokens.next(b)) {
          fail(name, cursor.line_number(), "malformed property '" + std::string(line) + "'");
        }
        property.name = std::string(b);
      }
      elements.back().properties.push_back(std::move(property));
    } else {
      fail(name, cursor.line_number(), "unexpected header line '" + std::string(line) + "'");
    }
  }
  if (!ended) fail(name, cursor.line_number(), "truncated: no end_header");
  if (!have_format) fail(name, cursor.line_number(), "no format line in the header");

  // Refuse counts the body cannot hold before allocating anything.
  std::size_t bytes_left = cursor.remaining_bytes();
  for (const Element& element : elements) {
    std::size_t min_bytes = 0;
    for (const Property& property : element.properties) {
      min_bytes += encoding == Encoding::ascii
                       ? 2
                       : scalar_size(property.is_list ? property.count_type : property.type);
    }
    if (min_bytes == 0) {
      // Nothing to read per item, yet a loop over `count` items: refuse instead of spinning.
      if (element.count > 0)
        fail(name, element.header_line, "element '" + element.name + "' has no properties");
      continue;
    }
    detail::check_count_fits(name, element.header_line, element.name.c_str(), element.count, min_bytes,
                             bytes_left);
    bytes_left -= static_cast<std::size_t>(element.count) * min_bytes;
  }

  const Element* vertex_element = nullptr;
  for (const Element& element : elements) {
    if (element.name == "vertex") vertex_element = &element;
  }
  if (vertex_element == nullptr) fail(name, cursor.line_number(), "no 'vertex' element");
  int xyz_slot[3] = {-1, -1, -1};
  for (std::size_t p = 0; p < vertex_element->properties.size(); ++p) {
    const Property& property = vertex_element->properties[p];
    for (int axis = 0; axis < 3; ++axis) {
      if (!property.is_list && property.name == std::string(1, static_cast<char>('x' + axis))) {
        xyz_slot[axis] = static_cast<int>(p);
      }
    }
  }
  if (xyz_slot[0] < 0 || xyz_slot[1] < 0 || xyz_slot[2] < 0) {
    fail(name, vertex_element->header_line, "the vertex element lacks an x, y or z property");
  }

  detail::MeshBuilder builder(name);
  std::int64_t face_total = 0;
  for (const Element& element : elements) {
    if (element.name != "face") continue;
    face_total = element.count;
    bool has_indices = false;
    for (const Property& property : element.properties) {
      has_indices |=
          property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index");
    }
    if (!has_indices) fail(name, element.header_line, "the face element lacks a vertex_indices list");
  }
  builder.reserve(static_cast<std::size_t>(vertex_element->count), static_cast<std::size_t>(face_total));

  BodyReader reader(contents.substr(cursor.offset()), encoding, cursor.line_number() + 1, name);
  std::vector<std::int64_t> polygon;
  for (const Element& element : elements) {
    const bool is_vertex = &element == vertex_element;
    const bool is_face = element.name == "face";
    for (std::int64_t item = 0; item < element.count; ++item) {
      double xyz[3] = {0.0, 0.0, 0.0};
      bool face_seen = false;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.is_list) {
          const double value = reader.read(property.type);
          if (is_vertex) {
            for (int axis = 0; axis < 3; ++axis) {
              if (xyz_slot[axis] == static_cast<int>(p)) xyz[axis] = value;
            }
          }
          continue;
        }
        const double length = reader.read(property.count_type);
        if (length < 0 || length > static_cast<double>(reader.bytes_left())) {
          fail(name, reader.line(),
               element.name + " " + std::to_string(item) + ": list length " +
                   std::to_string(static_cast<std::int64_t>(length)) + " does not fit the file");
        }
        const bool wanted =
            is_face && !face_seen && (property.name == "vertex_indices" || property.name == "vertex_index");
        if (wanted) polygon.clear();
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(length); ++k) {
          const double value = reader.read(property.type);
          if (wanted) polygon.push_back(static_cast<std::int64_t>(value));
        }
        if (wanted) {
          face_seen = true;
          builder.add_polygon(polygon, reader.line());
        }
      }
      if (is_vertex) builder.add_vertex(xyz[0], xyz[1], xyz[2], reader.line());
    }
  }
  return builder.finish();
}

}  // namespace pushpull::deform
