// Private pieces shared by the OFF/OBJ/PLY readers and writers.
#pragma once

// GCC 12 reports a false -Wrestrict inside std::string for `"literal" + std::string&&` (GCC bug 105329,
// fixed in GCC 13); the error messages below are built that way.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/mesh_io.hpp"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace pushpull::deform::detail {

// Shortest text that reads back to the same double (the writers' and the rewrite's numbers).
inline void append_number(std::string& out, double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc{} ? end : buffer);
}

// `text` as it can be quoted in a message: bytes outside printable ASCII as \xNN, at most `limit` bytes of it
// (then "..."): a binary file's first bytes named as its header wrote raw bytes to the terminal.
inline std::string printable(std::string_view text, std::size_t limit = 40) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (std::size_t k = 0; k < text.size() && k < limit; ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (text.size() > limit) out += "...";
  return out;
}

// A token as a message quotes it: 'token', printable().
inline std::string quoted_token(std::string_view token) {
  return "'" + printable(token) + "'";
}

// Why parse_double (text_scan.hpp) refused `token`: "'1e-400' is out of a double's range (it underflows to
// 0)", "... (it overflows)", or "'abc' is not a number".
inline std::string not_a_number_text(std::string_view token) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range && end == digits.data() + digits.size()) {
    // from_chars leaves value unchanged out of range; strtod says which way (HUGE_VAL: overflow).
    const std::string copy(digits);
    const bool over = std::isinf(std::strtod(copy.c_str(), nullptr));
    return quoted_token(token) + " is out of a double's range (" +
           (over ? "it overflows" : "it underflows to 0") + ")";
  }
  return quoted_token(token) + " is not a number";
}

[[noreturn]] inline void fail(const std::string& file, std::size_t line, const std::string& problem) {
  throw MeshIoError(file, line, problem);
}

// Collects vertices and fan-triangulated polygons while a file is parsed.
class MeshBuilder {
 public:
  explicit MeshBuilder(std::string name) : name_(std::move(name)) {}

  void reserve(std::size_t vertices, std::size_t triangles) {
    coords_.reserve(3 * vertices);
    triangles_.reserve(3 * triangles);
  }

  void add_vertex(double x, double y, double z, std::size_t line) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
      fail(name_, line, "vertex " + std::to_string(vertex_count()) + " has a NaN or infinite coordinate");
    }
    coords_.insert(coords_.end(), {x, y, z});
  }

  [[nodiscard]] std::size_t vertex_count() const { return coords_.size() / 3; }

  // Fan-triangulates one polygon of 0-based indices. The upper bound is checked in finish(), once all
  // vertices are known (an OBJ face may name a vertex defined further down).
  void add_polygon(const std::vector<std::int64_t>& polygon, std::size_t line) {
    if (polygon.size() < 3) {
      fail(name_, line, "face with " + std::to_string(polygon.size()) + " vertices (at least 3 needed)");
    }
    for (const std::int64_t index : polygon) {
      if (index < 0 || index > INT32_MAX) {
        fail(name_, line,
             "vertex index " + std::to_string(index) + " out of range (" +
                 (index < 0 ? std::string("indices are 0-based")
                            : "the file has " + std::to_string(vertex_count()) + " vertices so far") +
                 ")");
      }
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      triangles_.insert(triangles_.end(), {static_cast<int>(polygon[0]), static_cast<int>(polygon[k]),
                                           static_cast<int>(polygon[k + 1])});
      triangle_lines_.push_back(line);
    }
  }

  // The mesh, after checking that every index refers to an existing vertex.
  [[nodiscard]] Mesh finish() const {
    const auto vertices = static_cast<std::int64_t>(vertex_count());
    Mesh mesh;
    mesh.V.resize(static_cast<Eigen::Index>(vertex_count()), 3);
    for (std::size_t i = 0; i < vertex_count(); ++i) {
      for (int c = 0; c < 3; ++c)
        mesh.V(static_cast<Eigen::Index>(i), c) = coords_[3 * i + static_cast<std::size_t>(c)];
    }
    const std::size_t triangle_count = triangles_.size() / 3;
    mesh.F.resize(static_cast<Eigen::Index>(triangle_count), 3);
    for (std::size_t t = 0; t < triangle_count; ++t) {
      for (int c = 0; c < 3; ++c) {
        const int index = triangles_[3 * t + static_cast<std::size_t>(c)];
        if (index >= vertices) {
          fail(name_, triangle_lines_[t],
               "vertex index " + std::to_string(index) + " out of range (the file has " +
                   std::to_string(vertices) + " vertices)");
        }
        mesh.F(static_cast<Eigen::Index>(t), c) = index;
      }
    }
    return mesh;
  }

 private:
  std::string name_;
  std::vector<double> coords_;
  std::vector<int> triangles_;
  std::vector<std::size_t> triangle_lines_;
};

// Refuses a header count that cannot fit in the rest of the file (each item needs at least
// `min_bytes_each` bytes), before anything is allocated for it.
inline void check_count_fits(const std::string& file, std::size_t line, const char* what, std::int64_t count,
                             std::size_t min_bytes_each, std::size_t bytes_left) {
  if (count < 0) fail(file, line, std::string("negative ") + what + " count " + std::to_string(count));
  if (static_cast<std::uint64_t>(count) > bytes_left / min_bytes_each) {
    fail(file, line,
         std::string("header claims ") + std::to_string(count) + " " + what + " but only " +
             std::to_string(bytes_left) + " bytes follow (file truncated or count corrupt)");
  }
}

}  // namespace pushpull::deform::detail
