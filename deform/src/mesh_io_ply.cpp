// PLY reader: ASCII, binary little-endian and binary big-endian.
#include "mesh_io_detail.hpp"
#include "mesh_io_ply_header.hpp"
#include "text_scan.hpp"

#include <bit>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::deform {

using detail::fail;

namespace {

using detail::Element;
using detail::Encoding;
using detail::Property;
using detail::scalar_size;
using detail::ScalarType;

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

  // ASCII: the next token after the elements read, if any (data the header does not declare), and its line.
  // Whitespace, NUL and DOS end-of-file bytes and "comment" lines are not data.
  [[nodiscard]] std::string_view ascii_leftover() {
    for (;;) {
      while (pos_ < body_.size() && (detail::is_space(body_[pos_]) || body_[pos_] == '\n' ||
                                     body_[pos_] == '\0' || body_[pos_] == '\x1a')) {
        if (body_[pos_] == '\n') ++line_;
        ++pos_;
      }
      const std::size_t start = pos_;
      std::size_t end = start;
      while (end < body_.size() && !detail::is_space(body_[end]) && body_[end] != '\n' && body_[end] != '\0')
        ++end;
      const std::string_view token = body_.substr(start, end - start);
      if (token != "comment") return token;
      while (pos_ < body_.size() && body_[pos_] != '\n') ++pos_;  // the comment's line
    }
  }

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
    if (!detail::parse_double(token, value)) fail(name_, line_, detail::not_a_number_text(token));
    if (type != ScalarType::float32 && type != ScalarType::float64 &&
        value != static_cast<double>(static_cast<std::int64_t>(value))) {
      fail(name_, line_, detail::quoted_token(token) + " is not an integer");
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
  const detail::PlyHeader header = detail::read_ply_header(contents, name);
  const Encoding encoding = header.encoding;
  const std::vector<Element>& elements = header.elements;
  // Refuse counts the body cannot hold before allocating anything.
  std::size_t bytes_left = contents.size() - header.body_offset;
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
  if (vertex_element == nullptr) fail(name, header.body_line - 1, "no 'vertex' element");
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

  BodyReader reader(contents.substr(header.body_offset), encoding, header.body_line, name);
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
  // ASCII data after the declared elements: a count too small would drop faces unseen. (Binary files may
  // carry padding after their data; it is not read.)
  if (encoding == Encoding::ascii) {
    const std::string_view leftover = reader.ascii_leftover();
    if (!leftover.empty()) {
      fail(name, reader.line(),
           "more data after the elements the header declares ('" + detail::printable(leftover) +
               "'): is an element count in the header too small, or a property missing?");
    }
  }
  return builder.finish();
}

}  // namespace pushpull::deform
