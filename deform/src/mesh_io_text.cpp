// OFF and OBJ readers.
#include <algorithm>
#include "mesh_io_detail.hpp"
#include "text_scan.hpp"

#include <string>
#include <vector>

namespace pushpull::deform {

using detail::fail;

namespace {

// The next line that is neither empty nor a comment, or false at the end.
bool next_content_line(detail::LineCursor& cursor, std::string_view& line) {
  std::string_view raw;
  while (cursor.next(raw)) {
    line = detail::strip_comment(raw, '#');
    if (!line.empty()) return true;
  }
  return false;
}

std::vector<std::int64_t> read_ints(std::string_view line, const std::string& name, std::size_t line_no,
                                    const char* what) {
  std::vector<std::int64_t> values;
  detail::Tokens tokens(line);
  std::string_view token;
  while (tokens.next(token)) {
    std::int64_t value = 0;
    if (!detail::parse_int64(token, value)) {
      fail(name, line_no,
           std::string("expected an integer in the ") + what + ", found " + detail::quoted_token(token));
    }
    values.push_back(value);
  }
  return values;
}

}  // namespace

Mesh parse_off(std::string_view contents, const std::string& name) {
  detail::LineCursor cursor(contents);
  std::string_view line;
  if (!next_content_line(cursor, line)) fail(name, 0, "empty file (expected an OFF header)");

  detail::Tokens header(line);
  std::string_view keyword;
  header.next(keyword);
  // Header keyword: OFF or a 3D variant (COFF, NOFF, CNOFF, STOFF, ...); 4OFF and nOFF (other
  // dimensions) are refused.
  const bool off_keyword = keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF" &&
                           keyword.find('4') == std::string_view::npos && keyword.front() != 'n';
  if (!off_keyword) {
    fail(name, cursor.line_number(), "not an OFF file (header '" + detail::printable(keyword) + "')");
  }
  // The counts may share the header line or follow on the next one.
  std::string_view rest =
      line.substr(static_cast<std::size_t>(keyword.data() + keyword.size() - line.data()));
  rest = detail::strip_comment(rest, '#');
  if (rest.empty()) {
    if (!next_content_line(cursor, line))
      fail(name, cursor.line_number(), "truncated: missing the vertex/face counts");
    rest = line;
  }
  const std::size_t counts_line = cursor.line_number();
  const std::vector<std::int64_t> counts = read_ints(rest, name, counts_line, "counts line");
  if (counts.size() < 2) fail(name, counts_line, "expected 'vertices faces [edges]' counts");
  const std::int64_t vertex_count = counts[0];
  const std::int64_t face_count = counts[1];
  // The counts must fit the bytes that follow, counting any record as at least "x\n" (a short record, "0 0"
  // for a vertex or "2 0 1" for a face, is then read and refused for what it is, not as a corrupt count);
  // memory is reserved for at most as many as well-formed records ("0 0 0\n", "3 0 0 0\n") would fit.
  const std::size_t bytes_left = cursor.remaining_bytes() + 1;  // (the last line may lack its '\n')
  detail::check_count_fits(name, counts_line, "vertices", vertex_count, 2, bytes_left);
  detail::check_count_fits(name, counts_line, "faces", face_count, 2,
                           bytes_left - 2 * static_cast<std::size_t>(vertex_count));

  detail::MeshBuilder builder(name);
  builder.reserve(std::min(static_cast<std::size_t>(vertex_count), bytes_left / 6),
                  std::min(static_cast<std::size_t>(face_count), bytes_left / 8));
  for (std::int64_t i = 0; i < vertex_count; ++i) {
    if (!next_content_line(cursor, line)) {
      fail(name, cursor.line_number(),
           "truncated: " + std::to_string(i) + " of " + std::to_string(vertex_count) + " vertices read");
    }
    detail::Tokens tokens(line);
    double xyz[3];
    for (double& value : xyz) {
      std::string_view token;
      if (!tokens.next(token))
        fail(name, cursor.line_number(), "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
      if (!detail::parse_double(token, value)) {
        fail(name, cursor.line_number(),
             "vertex " + std::to_string(i) + ": " + detail::not_a_number_text(token));
      }
    }
    builder.add_vertex(xyz[0], xyz[1], xyz[2], cursor.line_number());
  }
  std::vector<std::int64_t> polygon;
  for (std::int64_t f = 0; f < face_count; ++f) {
    if (!next_content_line(cursor, line)) {
      fail(name, cursor.line_number(),
           "truncated: " + std::to_string(f) + " of " + std::to_string(face_count) + " faces read");
    }
    detail::Tokens tokens(line);
    std::string_view token;
    tokens.next(token);
    std::int64_t n = 0;
    if (!detail::parse_int64(token, n) || n < 0) {
      fail(name, cursor.line_number(),
           "face " + std::to_string(f) + ": bad vertex count " + detail::quoted_token(token));
    }
    if (static_cast<std::size_t>(n) > line.size()) {
      fail(name, cursor.line_number(),
           "face " + std::to_string(f) + " claims " + std::to_string(n) + " vertices");
    }
    polygon.assign(static_cast<std::size_t>(n), 0);
    for (std::int64_t k = 0; k < n; ++k) {
      if (!tokens.next(token)) {
        fail(name, cursor.line_number(),
             "face " + std::to_string(f) + " lists fewer than " + std::to_string(n) + " vertices");
      }
      if (!detail::parse_int64(token, polygon[static_cast<std::size_t>(k)])) {
        fail(name, cursor.line_number(),
             "face " + std::to_string(f) + ": " + detail::quoted_token(token) + " is not an index");
      }
    }
    builder.add_polygon(polygon, cursor.line_number());  // trailing colour values are ignored
  }
  // Records after the declared faces: a header count too small would drop them unseen (holes in the surface).
  if (next_content_line(cursor, line)) {
    detail::Tokens tokens(line);
    std::string_view token;
    tokens.next(token);
    fail(name, cursor.line_number(),
         "more data after the " + std::to_string(face_count) + " faces the header declares ('" +
             detail::printable(token) + "'): is the header's vertex or face count too small?");
  }
  return builder.finish();
}

Mesh parse_obj(std::string_view contents, const std::string& name) {
  detail::LineCursor cursor(contents);
  detail::MeshBuilder builder(name);
  std::string_view line;
  std::vector<std::int64_t> polygon;
  while (next_content_line(cursor, line)) {
    detail::Tokens tokens(line);
    std::string_view keyword;
    tokens.next(keyword);
    // A line ending in a backslash goes on on the next one: refused where this reader needs the line.
    if (keyword == "v" || keyword == "f") {
      const std::size_t last = line.find_last_not_of(" \t\r");
      if (last != std::string_view::npos && line[last] == '\\')
        fail(name, cursor.line_number(),
             "a line continued with '\\' is not supported (join it with the next line)");
    }
    if (keyword == "v") {
      double xyz[3];
      for (double& value : xyz) {
        std::string_view token;
        if (!tokens.next(token)) fail(name, cursor.line_number(), "vertex with fewer than 3 coordinates");
        if (!detail::parse_double(token, value)) {
          fail(name, cursor.line_number(), detail::not_a_number_text(token));
        }
      }
      builder.add_vertex(xyz[0], xyz[1], xyz[2], cursor.line_number());
    } else if (keyword == "f") {
      polygon.clear();
      std::string_view token;
      while (tokens.next(token)) {
        // "a", "a/b", "a//c", "a/b/c": the position index is the part before the first slash.
        const std::string_view position = token.substr(0, token.find('/'));
        std::int64_t index = 0;
        if (!detail::parse_int64(position, index) || index == 0) {
          fail(name, cursor.line_number(), "bad face vertex " + detail::quoted_token(token));
        }
        // Positive indices are 1-based; negative ones count back from the latest vertex.
        polygon.push_back(index > 0 ? index - 1 : static_cast<std::int64_t>(builder.vertex_count()) + index);
        if (polygon.back() < 0) {
          fail(name, cursor.line_number(),
               "relative index " + std::to_string(index) + " reaches before the first vertex");
        }
      }
      builder.add_polygon(polygon, cursor.line_number());
    }
    // vt, vn, g, o, s, usemtl, mtllib, l, p and the rest carry nothing this reader needs.
  }
  return builder.finish();
}

}  // namespace pushpull::deform
