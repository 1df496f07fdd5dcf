// A mesh file with its vertex positions replaced and everything else kept as written (mesh_io.hpp:
// rewrite_positions).
#include "mesh_io_detail.hpp"
#include "mesh_io_ply_header.hpp"
#include "text_scan.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::deform {

using detail::append_number;
using detail::fail;

namespace {

// Builds the rewritten contents: the source's bytes with some number tokens replaced, in file order.
class SpanEditor {
 public:
  explicit SpanEditor(std::string_view contents) : contents_(contents) { out_.reserve(contents.size() + 64); }

  // Replaces the token `token` (a view into the contents, after the last one replaced) by `value`'s shortest
  // text, unless the token already reads as exactly that number: a vertex that did not move keeps its text.
  void replace(std::string_view token, double value) {
    double written = 0.0;
    if (detail::parse_double(token, written) && written == value &&
        std::signbit(written) == std::signbit(value))
      return;
    const std::size_t start = static_cast<std::size_t>(token.data() - contents_.data());
    out_.append(contents_.substr(copied_, start - copied_));
    append_number(out_, value);
    copied_ = start + token.size();
  }

  std::string finish() {
    out_.append(contents_.substr(copied_));
    return std::move(out_);
  }

 private:
  std::string_view contents_;
  std::string out_;
  std::size_t copied_ = 0;
};

// The first three whitespace-separated tokens of `line` from token number `first` on (before any '#'), into
// `tokens`; false when the line has too few.
bool three_tokens(std::string_view line, int first, std::string_view (&tokens)[3]) {
  detail::Tokens scan(line.substr(0, line.find('#')));
  std::string_view token;
  for (int k = 0; k < first; ++k)
    if (!scan.next(token)) return false;
  for (std::string_view& t : tokens)
    if (!scan.next(t)) return false;
  return true;
}

void check_rows(const Eigen::MatrixXd& V, std::int64_t file_vertices, const std::string& name) {
  if (V.rows() != file_vertices || V.cols() != 3)
    fail(name, 0,
         "has " + std::to_string(file_vertices) + " vertices, the positions to write " +
             std::to_string(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite() && !V.row(i).array().isNaN().all())
      fail(name, 0, "the position to write of vertex " + std::to_string(i) + " is not finite");
}

// A row of NaN: the vertex keeps its coordinates as written.
bool keep(const Eigen::MatrixXd& V, Eigen::Index i) {
  return std::isnan(V(i, 0));
}

// The next line that is neither empty nor a comment, or false at the end.
bool next_content_line(detail::LineCursor& cursor, std::string_view& raw) {
  while (cursor.next(raw))
    if (!detail::strip_comment(raw, '#').empty()) return true;
  return false;
}

PositionRewrite rewrite_off(std::string_view contents, const Eigen::MatrixXd& V, const std::string& name) {
  // Read as parse_off reads it: the header keyword, the counts (on the header line or the next), then one
  // vertex per content line.
  detail::LineCursor cursor(contents);
  std::string_view raw;
  if (!next_content_line(cursor, raw)) fail(name, 0, "empty file (expected an OFF header)");
  std::string_view line = detail::strip_comment(raw, '#');
  detail::Tokens header(line);
  std::string_view keyword;
  header.next(keyword);
  std::string_view rest = detail::strip_comment(
      line.substr(static_cast<std::size_t>(keyword.data() + keyword.size() - line.data())), '#');
  if (rest.empty()) {
    if (!next_content_line(cursor, raw)) fail(name, cursor.line_number(), "truncated: missing the counts");
    rest = detail::strip_comment(raw, '#');
  }
  detail::Tokens counts(rest);
  std::string_view first;
  std::int64_t vertex_count = -1;
  if (!counts.next(first) || !detail::parse_int64(first, vertex_count) || vertex_count < 0)
    fail(name, cursor.line_number(), "expected 'vertices faces [edges]' counts");
  check_rows(V, vertex_count, name);
  PositionRewrite result;
  // NOFF, CNOFF, ...: per-vertex normals, kept as written.
  if (keyword.substr(0, keyword.size() - 3).find('N') != std::string_view::npos)
    result.stale.emplace_back("per-vertex normals");
  SpanEditor editor(contents);
  for (std::int64_t i = 0; i < vertex_count; ++i) {
    if (!next_content_line(cursor, raw))
      fail(name, cursor.line_number(), "truncated: " + std::to_string(i) + " vertices");
    std::string_view xyz[3];
    if (!three_tokens(raw, 0, xyz))
      fail(name, cursor.line_number(), "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
    if (keep(V, i)) continue;
    for (int axis = 0; axis < 3; ++axis) editor.replace(xyz[axis], V(i, axis));
  }
  result.contents = editor.finish();
  return result;
}

PositionRewrite rewrite_obj(std::string_view contents, const Eigen::MatrixXd& V, const std::string& name) {
  detail::LineCursor cursor(contents);
  std::string_view raw;
  std::vector<std::string_view> vertex_lines;
  bool normals = false;
  while (next_content_line(cursor, raw)) {
    detail::Tokens tokens(detail::strip_comment(raw, '#'));
    std::string_view keyword;
    tokens.next(keyword);
    if (keyword == "v") vertex_lines.push_back(raw);
    normals |= keyword == "vn";
  }
  check_rows(V, static_cast<std::int64_t>(vertex_lines.size()), name);
  PositionRewrite result;
  if (normals) result.stale.emplace_back("normals (vn)");
  SpanEditor editor(contents);
  for (std::size_t i = 0; i < vertex_lines.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    std::string_view xyz[3];
    if (!three_tokens(vertex_lines[i], 1, xyz))  // after the keyword
      fail(name, 0, "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
    if (keep(V, row)) continue;
    for (int axis = 0; axis < 3; ++axis) editor.replace(xyz[axis], V(row, axis));
  }
  result.contents = editor.finish();
  return result;
}

// Writes `value` as `type` (a float type) in the file's byte order at `at`.
void store(char* at, detail::ScalarType type, double value, bool little_endian) {
  unsigned char bytes[8];
  std::size_t size = 8;
  if (type == detail::ScalarType::float32) {
    const auto narrow = static_cast<float>(value);
    std::memcpy(bytes, &narrow, 4);
    size = 4;
  } else {
    std::memcpy(bytes, &value, 8);
  }
  if (little_endian != (std::endian::native == std::endian::little))
    for (std::size_t i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
  std::memcpy(at, bytes, size);
}

PositionRewrite rewrite_ply(std::string_view contents, const Eigen::MatrixXd& V, const std::string& name) {
  using detail::Encoding;
  using detail::ScalarType;
  const detail::PlyHeader header = detail::read_ply_header(contents, name);
  std::size_t vertex_index = header.elements.size();
  for (std::size_t e = 0; e < header.elements.size(); ++e)
    if (header.elements[e].name == "vertex") vertex_index = e;
  if (vertex_index == header.elements.size()) fail(name, header.body_line - 1, "no 'vertex' element");
  const detail::Element& vertex = header.elements[vertex_index];
  check_rows(V, vertex.count, name);
  int slots[3] = {-1, -1, -1};
  bool normals = false;
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    const detail::Property& property = vertex.properties[p];
    if (property.is_list)
      fail(name, vertex.header_line, "its vertex element has a list property: cannot rewrite it in place");
    for (int axis = 0; axis < 3; ++axis)
      if (property.name == std::string(1, static_cast<char>('x' + axis))) slots[axis] = static_cast<int>(p);
    normals |= property.name == "nx";
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (slots[axis] < 0) fail(name, vertex.header_line, "the vertex element lacks an x, y or z property");
    const ScalarType type = vertex.properties[static_cast<std::size_t>(slots[axis])].type;
    if (type != ScalarType::float32 && type != ScalarType::float64)
      fail(name, vertex.header_line, "integer coordinates: cannot rewrite them in place");
  }
  PositionRewrite result;
  if (normals) result.stale.emplace_back("normals (nx, ny, nz)");

  if (header.encoding == Encoding::ascii) {
    // The body as parse_ply reads it: one stream of whitespace-separated tokens (line breaks mean nothing),
    // each scalar one token, each list its length and then its items; the vertices' x, y and z tokens are
    // replaced where they are.
    const std::string_view body = contents.substr(header.body_offset);
    std::size_t pos = 0;
    auto next_token = [&](std::string_view& token) {
      while (pos < body.size() && (detail::is_space(body[pos]) || body[pos] == '\n')) ++pos;
      if (pos >= body.size()) return false;
      const std::size_t start = pos;
      while (pos < body.size() && !detail::is_space(body[pos]) && body[pos] != '\n') ++pos;
      token = body.substr(start, pos - start);
      return true;
    };
    SpanEditor editor(contents);
    std::string_view token;
    for (std::size_t e = 0; e <= vertex_index; ++e) {
      const detail::Element& element = header.elements[e];
      for (std::int64_t item = 0; item < element.count; ++item) {
        std::string_view xyz[3];
        for (std::size_t p = 0; p < element.properties.size(); ++p) {
          if (!next_token(token)) fail(name, 0, "truncated: the data ends before the vertices were read");
          if (!element.properties[p].is_list) {
            for (int axis = 0; axis < 3 && e == vertex_index; ++axis)
              if (slots[axis] == static_cast<int>(p)) xyz[axis] = token;
            continue;
          }
          std::int64_t length = 0;
          if (!detail::parse_int64(token, length) || length < 0)
            fail(name, 0,
                 element.name + " " + std::to_string(item) + ": bad list length " +
                     detail::quoted_token(token));
          for (std::int64_t k = 0; k < length; ++k)
            if (!next_token(token)) fail(name, 0, "truncated: the data ends before the vertices were read");
        }
        if (e != vertex_index || keep(V, item)) continue;
        // In file order, whatever the order of x, y and z among the properties.
        int order[3] = {0, 1, 2};
        std::sort(order, order + 3, [&](int a, int b) { return slots[a] < slots[b]; });
        for (const int axis : order) editor.replace(xyz[axis], V(item, axis));
      }
    }
    result.contents = editor.finish();
    return result;
  }

  // Binary: every item before the vertices and every vertex of fixed size.
  std::size_t offset = header.body_offset;
  for (std::size_t e = 0; e < vertex_index; ++e) {
    std::size_t item = 0;
    for (const detail::Property& property : header.elements[e].properties) {
      if (property.is_list)
        fail(name, header.elements[e].header_line,
             "element '" + header.elements[e].name +
                 "' before the vertices has a list: cannot rewrite in place");
      item += detail::scalar_size(property.type);
    }
    offset += item * static_cast<std::size_t>(header.elements[e].count);
  }
  std::size_t record = 0, at[3] = {0, 0, 0};
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    for (int axis = 0; axis < 3; ++axis)
      if (slots[axis] == static_cast<int>(p)) at[axis] = record;
    record += detail::scalar_size(vertex.properties[p].type);
  }
  if (offset > contents.size() || record * static_cast<std::size_t>(vertex.count) > contents.size() - offset)
    fail(name, 0, "truncated: the vertices do not fit the file");
  result.contents.assign(contents);
  const bool little = header.encoding == Encoding::binary_le;
  for (std::int64_t i = 0; i < vertex.count; ++i) {
    if (keep(V, i)) continue;
    char* item = result.contents.data() + offset + static_cast<std::size_t>(i) * record;
    for (int axis = 0; axis < 3; ++axis)
      store(item + at[axis], vertex.properties[static_cast<std::size_t>(slots[axis])].type, V(i, axis),
            little);
  }
  return result;
}

}  // namespace

PositionRewrite rewrite_positions(std::string_view contents, MeshFormat format, const Eigen::MatrixXd& V,
                                  const std::string& name) {
  switch (format) {
    case MeshFormat::off:
      return rewrite_off(contents, V, name);
    case MeshFormat::obj:
      return rewrite_obj(contents, V, name);
    case MeshFormat::ply:
      return rewrite_ply(contents, V, name);
  }
  fail(name, 0, "unknown mesh format");
}

}  // namespace pushpull::deform
