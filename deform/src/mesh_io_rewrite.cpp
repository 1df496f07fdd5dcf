// A mesh file with its vertex positions replaced and everything else kept as written (mesh_io.hpp:
// rewrite_positions).
#include "mesh_io_detail.hpp"
#include "mesh_io_ply_header.hpp"
#include "text_scan.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace pushpull::deform {

using detail::fail;

namespace {

// Shortest text that reads back to the same double.
void append_number(std::string& out, double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc{} ? end : buffer);
}

// Builds the rewritten contents: the source's bytes, some of its lines replaced.
class LineEditor {
 public:
  explicit LineEditor(std::string_view contents) : contents_(contents) { out_.reserve(contents.size() + 64); }

  // Replaces, in `line` (a view into the contents, after the last one edited), the whitespace-separated
  // tokens numbered slots[i] (0-based, ascending; counted before any '#' comment) by values[i]; the rest of
  // the line, its spacing and comment included, stays. Returns false (nothing changed) when the line has too
  // few tokens.
  bool replace(std::string_view line, const int (&slots)[3], const double (&values)[3]) {
    const std::string_view content = line.substr(0, line.find('#'));
    std::size_t spans[3][2] = {};
    std::size_t pos = 0;
    int found = 0;
    for (int token = 0; found < 3; ++token) {
      while (pos < content.size() && detail::is_space(content[pos])) ++pos;
      if (pos >= content.size()) return false;
      const std::size_t start = pos;
      while (pos < content.size() && !detail::is_space(content[pos])) ++pos;
      if (token == slots[found]) {
        spans[found][0] = start;
        spans[found][1] = pos;
        ++found;
      }
    }
    const std::size_t line_start = static_cast<std::size_t>(line.data() - contents_.data());
    out_.append(contents_.substr(copied_, line_start - copied_));
    std::size_t last = 0;
    for (int i = 0; i < 3; ++i) {
      out_.append(line.substr(last, spans[i][0] - last));
      append_number(out_, values[i]);
      last = spans[i][1];
    }
    out_.append(line.substr(last));
    copied_ = line_start + line.size();
    return true;
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
  LineEditor editor(contents);
  const int slots[3] = {0, 1, 2};
  for (std::int64_t i = 0; i < vertex_count; ++i) {
    if (!next_content_line(cursor, raw))
      fail(name, cursor.line_number(), "truncated: " + std::to_string(i) + " vertices");
    if (keep(V, i)) continue;
    const double values[3] = {V(i, 0), V(i, 1), V(i, 2)};
    if (!editor.replace(raw, slots, values))
      fail(name, cursor.line_number(), "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
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
  LineEditor editor(contents);
  const int slots[3] = {1, 2, 3};  // after the keyword
  for (std::size_t i = 0; i < vertex_lines.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (keep(V, row)) continue;
    const double values[3] = {V(row, 0), V(row, 1), V(row, 2)};
    if (!editor.replace(vertex_lines[i], slots, values))
      fail(name, 0, "vertex " + std::to_string(i) + " has fewer than 3 coordinates");
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
    if (header.encoding != Encoding::ascii && type != ScalarType::float32 && type != ScalarType::float64)
      fail(name, vertex.header_line, "integer coordinates: cannot rewrite them in place");
  }
  PositionRewrite result;
  if (normals) result.stale.emplace_back("normals (nx, ny, nz)");

  if (header.encoding == Encoding::ascii) {
    // One item per line (as PLY writers write them): the lines of the elements before the vertex element are
    // skipped. (The line editor takes the tokens in order.)
    if (!(slots[0] < slots[1] && slots[1] < slots[2]))
      fail(name, vertex.header_line, "x, y and z not in that order: cannot rewrite them in place");
    detail::LineCursor cursor(contents.substr(header.body_offset));
    std::string_view raw;
    std::int64_t skip = 0;
    for (std::size_t e = 0; e < vertex_index; ++e) skip += header.elements[e].count;
    for (std::int64_t i = 0; i < skip; ++i)
      if (!cursor.next(raw)) fail(name, 0, "truncated before the vertices");
    // LineEditor wants views into the whole contents: the cursor's are (a substring of it).
    LineEditor editor(contents);
    for (std::int64_t i = 0; i < vertex.count; ++i) {
      if (!cursor.next(raw)) fail(name, 0, "truncated: " + std::to_string(i) + " vertices");
      detail::Tokens tokens(raw);
      std::string_view token;
      std::size_t n = 0;
      while (tokens.next(token)) ++n;
      if (n != vertex.properties.size())
        fail(name, header.body_line + static_cast<std::size_t>(skip + i),
             "vertex " + std::to_string(i) + " is not one line of its " +
                 std::to_string(vertex.properties.size()) + " properties: cannot rewrite it in place");
      if (keep(V, i)) continue;
      const double values[3] = {V(i, 0), V(i, 1), V(i, 2)};
      (void)editor.replace(raw, slots, values);
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
