#include "mesh_io_ply_header.hpp"

#include "mesh_io_detail.hpp"
#include "text_scan.hpp"

namespace pushpull::deform::detail {

PlyHeader read_ply_header(std::string_view contents, const std::string& name) {
  detail::LineCursor cursor(contents);
  std::string_view line;
  if (!cursor.next(line) || detail::strip_comment(line, '\0') != "ply")
    fail(name, 1, "not a PLY file (no 'ply' magic)");

  PlyHeader header;
  Encoding& encoding = header.encoding;
  bool have_format = false;
  std::vector<Element>& elements = header.elements;
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
        fail(name, cursor.line_number(), "unknown PLY format '" + detail::printable(a) + "'");
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

  header.body_offset = cursor.offset();
  header.body_line = cursor.line_number() + 1;
  return header;
}

}  // namespace pushpull::deform::detail
