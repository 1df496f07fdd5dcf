// Mesh file dispatch by extension, the writers, and atomic file replacement.
#include "mesh_io_detail.hpp"
#include "mesh_io_ply_header.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pushpull::deform {

using detail::append_number;

namespace {

std::string describe(const std::string& file, std::size_t line, const std::string& problem) {
  return line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem;
}

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) detail::fail(path.string(), 0, std::string("cannot open for reading: ") + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) detail::fail(path.string(), 0, "read error");
  return bytes;
}

void check_faces(const Mesh& mesh, const std::string& name) {
  if (mesh.V.cols() != 3 || mesh.F.cols() != 3)
    detail::fail(name, 0, "mesh to write is not #V by 3 / #F by 3");
  if (mesh.F.size() > 0 && (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows())) {
    detail::fail(name, 0, "mesh to write has a face index out of range");
  }
}

void append_vertex_row(std::string& out, const Mesh& mesh, Eigen::Index i) {
  append_number(out, mesh.V(i, 0));
  out += ' ';
  append_number(out, mesh.V(i, 1));
  out += ' ';
  append_number(out, mesh.V(i, 2));
}

// One triangle as text: `prefix` then the three indices plus `base` (1 for OBJ). Appended piecewise:
// GCC 12 warns falsely (-Wrestrict) on long std::string operator+ chains.
void append_face(std::string& out, const char* prefix, const Mesh& mesh, Eigen::Index f, int base) {
  out += prefix;
  for (int c = 0; c < 3; ++c) {
    char buffer[16];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, mesh.F(f, c) + base);
    if (c > 0) out += ' ';
    out.append(buffer, ec == std::errc{} ? end : buffer);
  }
  out += '\n';
}

template <typename T>
void append_binary(std::string& out, T value) {
  static_assert(std::endian::native == std::endian::little, "binary PLY writer assumes a little-endian host");
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

MeshIoError::MeshIoError(std::string file, std::size_t line, const std::string& problem)
    : std::runtime_error(describe(file, line, problem)), file_(std::move(file)), line_(line) {}

std::optional<MeshFormat> mesh_format_from_path(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".off") return MeshFormat::off;
  if (extension == ".obj") return MeshFormat::obj;
  if (extension == ".ply") return MeshFormat::ply;
  return std::nullopt;
}

Mesh read_mesh(const std::filesystem::path& path) {
  const std::optional<MeshFormat> format = mesh_format_from_path(path);
  if (!format) detail::fail(path.string(), 0, "unknown mesh format (expected .off, .obj or .ply)");
  const std::string bytes = read_whole_file(path);
  switch (*format) {
    case MeshFormat::off:
      return parse_off(bytes, path.string());
    case MeshFormat::obj:
      return parse_obj(bytes, path.string());
    case MeshFormat::ply:
      return parse_ply(bytes, path.string());
  }
  detail::fail(path.string(), 0, "unknown mesh format");
}

std::string format_off(const Mesh& mesh) {
  check_faces(mesh, "OFF output");
  std::string out = "OFF\n";
  out += std::to_string(mesh.V.rows());
  out += ' ';
  out += std::to_string(mesh.F.rows());
  out += " 0\n";
  out.reserve(out.size() + static_cast<std::size_t>(mesh.V.rows()) * 60 +
              static_cast<std::size_t>(mesh.F.rows()) * 24);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    append_vertex_row(out, mesh, i);
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    append_face(out, "3 ", mesh, f, 0);
  }
  return out;
}

std::string format_obj(const Mesh& mesh) {
  check_faces(mesh, "OBJ output");
  std::string out = "# pushpull\n";
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    out += "v ";
    append_vertex_row(out, mesh, i);
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    append_face(out, "f ", mesh, f, 1);
  }
  return out;
}

std::string format_ply(const Mesh& mesh, PlyEncoding encoding) {
  check_faces(mesh, "PLY output");
  const bool ascii = encoding == PlyEncoding::ascii;
  std::string out = std::string("ply\nformat ") + (ascii ? "ascii" : "binary_little_endian") +
                    " 1.0\ncomment pushpull\nelement vertex " + std::to_string(mesh.V.rows()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(mesh.F.rows()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    if (ascii) {
      append_vertex_row(out, mesh, i);
      out += '\n';
    } else {
      for (int c = 0; c < 3; ++c) append_binary<double>(out, mesh.V(i, c));
    }
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (ascii) {
      append_face(out, "3 ", mesh, f, 0);
    } else {
      append_binary<std::uint8_t>(out, 3);
      for (int c = 0; c < 3; ++c) append_binary<std::int32_t>(out, mesh.F(f, c));
    }
  }
  return out;
}

namespace {

// Atomically, errors as MeshIoError naming the path once.
void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  try {
    write_file_atomically(path, bytes);
  } catch (const std::runtime_error& e) {
    // write_file_atomically's message starts with the path; MeshIoError adds it again.
    std::string problem = e.what();
    const std::string prefix = path.string() + ": ";
    if (problem.rfind(prefix, 0) == 0) problem.erase(0, prefix.size());
    throw MeshIoError(path.string(), 0, problem);
  }
}

}  // namespace

void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const MeshWriteOptions& options) {
  const std::optional<MeshFormat> format = mesh_format_from_path(path);
  if (!format) detail::fail(path.string(), 0, "unknown mesh format (expected .off, .obj or .ply)");
  std::string bytes;
  switch (*format) {
    case MeshFormat::off:
      bytes = format_off(mesh);
      break;
    case MeshFormat::obj:
      bytes = format_obj(mesh);
      break;
    case MeshFormat::ply:
      bytes = format_ply(mesh, options.ply_encoding);
      break;
  }
  write_bytes(path, bytes);
}

std::vector<std::string> write_deformed_mesh(const std::filesystem::path& path,
                                             const std::filesystem::path& source,
                                             const Eigen::MatrixXd& source_positions, const Mesh& mesh) {
  const std::optional<MeshFormat> format = mesh_format_from_path(path);
  if (!format || mesh_format_from_path(source) != format) {
    write_mesh(path, mesh);
    return {};
  }
  const std::string contents = read_whole_file(source);
  std::optional<PositionRewrite> rewrite;
  std::string refused;
  try {
    rewrite = rewrite_positions(contents, *format, source_positions, source.string());
  } catch (const MeshIoError& e) {  // a layout it cannot rewrite in place (or a source changed since)
    refused = e.what();
  }
  if (!rewrite) {
    MeshWriteOptions fallback;  // an ASCII PLY falls back to ASCII
    if (*format == MeshFormat::ply) {
      try {
        if (detail::read_ply_header(contents, source.string()).encoding == detail::Encoding::ascii)
          fallback.ply_encoding = PlyEncoding::ascii;
      } catch (const MeshIoError&) {  // no header to go by: the default encoding
      }
    }
    write_mesh(path, mesh, fallback);
    return {"written as triangles with positions only, not as a copy of the input (" + refused + ")"};
  }
  write_bytes(path, rewrite->contents);
  std::vector<std::string> notes;
  for (const std::string& kept : rewrite->stale)
    notes.push_back("the input's " + kept +
                    " are kept as they were: they do not follow the deformed surface");
  return notes;
}

}  // namespace pushpull::deform
