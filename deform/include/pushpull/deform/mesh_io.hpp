// Reading and writing triangle meshes in the plain geometry formats used by tests and batch runs:
// OFF, OBJ and PLY. (glTF/GLB/Draco models go through pushpull::assets, not through here.)
//
// Reading: polygons are fan-triangulated (v0 v1 v2, v0 v2 v3, ...); colours, normals, texture
// coordinates and any other attributes are ignored. OBJ `f a/b/c` and negative (relative) indices
// are understood. PLY may be ASCII, binary little-endian or binary big-endian; it must have a
// `vertex` element with float/double properties x, y, z and a `face` element with a list property
// `vertex_indices` (or `vertex_index`); other elements and properties are skipped.
// Every problem (unreadable file, truncated data, counts that do not fit the file, index out of
// range, NaN or infinite coordinates, faces with fewer than 3 vertices) throws MeshIoError whose
// message names the file, the line where there is one, and the problem. Counts in a header are
// checked against the file size before anything is allocated.
//
// Writing: the format follows the extension (.off, .obj, .ply); coordinates are written as their shortest
// text that reads back bit-exactly. write_mesh writes triangles and positions; write_deformed_mesh keeps
// everything else a source file of the same format held (its polygons, attributes and comments). The file is
// written atomically: the bytes go to a temporary file in the same folder that is then renamed over the
// target, so a reader never sees a half-written mesh.
//
// Units and frame: whatever the file uses; nothing is scaled or transformed.
// Thread-safety: the functions share no state; concurrent calls on different files are safe.
#pragma once

#include "pushpull/deform/file_output.hpp"  // write_file_atomically, for the callers that write other files
#include "pushpull/deform/mesh.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pushpull::deform {

enum class MeshFormat { off, obj, ply };

// A mesh file could not be read or written. file() and line() (1-based, 0 when not applicable) locate
// the problem; what() is the full readable message "FILE:LINE: PROBLEM".
class MeshIoError : public std::runtime_error {
 public:
  MeshIoError(std::string file, std::size_t line, const std::string& problem);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

// The format named by the file extension (case-insensitive), or nullopt for anything else.
[[nodiscard]] std::optional<MeshFormat> mesh_format_from_path(const std::filesystem::path& path);

// Reads a mesh; the format follows the extension. Throws MeshIoError.
[[nodiscard]] Mesh read_mesh(const std::filesystem::path& path);

// Parses file contents already in memory. `name` is only used in error messages.
[[nodiscard]] Mesh parse_off(std::string_view contents, const std::string& name);
[[nodiscard]] Mesh parse_obj(std::string_view contents, const std::string& name);
[[nodiscard]] Mesh parse_ply(std::string_view contents, const std::string& name);

enum class PlyEncoding { binary_little_endian, ascii };

struct MeshWriteOptions {
  PlyEncoding ply_encoding = PlyEncoding::binary_little_endian;
};

// Writes a mesh atomically; the format follows the extension. Throws MeshIoError (unknown extension,
// F indices out of range, I/O failure).
void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const MeshWriteOptions& options = {});

// What rewrite_positions made: the file's new contents, and the attributes it kept as written that follow
// the positions (normals, no longer normal to the moved surface), named for a warning ("normals (vn)").
struct PositionRewrite {
  std::string contents;
  std::vector<std::string> stale;
};

// The contents of a mesh file of `format` with its vertex positions replaced by V's rows (#V by 3, one row
// per vertex as read_mesh reads them; a row of NaN keeps that vertex as written) and everything else as
// written: polygons stay polygons, and comments, colours, texture coordinates, normals, groups and materials
// stay. Text formats (OFF, OBJ, ASCII PLY): the tokens read_mesh reads as a vertex's x, y and z are replaced
// by their shortest round-trip text, unless they already read as exactly the new value (an unmoved vertex
// keeps its text); every other byte stays. Binary PLY: the coordinates in the file's own float type and byte
// order, every other byte as it was. Throws MeshIoError (naming `name`) where V does not fit the file, or its
// layout cannot be rewritten in place: a PLY vertex element with a list property or integer coordinates, a
// binary PLY whose vertices follow an element with a list.
[[nodiscard]] PositionRewrite rewrite_positions(std::string_view contents, MeshFormat format,
                                                const Eigen::MatrixXd& V, const std::string& name);

// Writes a deformed mesh to `path`: where `source` is a mesh file of path's format, as a copy of it with the
// positions replaced by source_positions (rewrite_positions: its polygons, attributes and comments kept),
// else, or where rewrite_positions refuses its layout, `mesh` as write_mesh writes it. source_positions: one
// row per vertex of the source (read_mesh's vertices); a row of NaN keeps that vertex as written (one the
// mesh does not use). Returns notes for the user: attributes kept that no longer match the surface (normals),
// or why it was written as triangles. Throws MeshIoError (reading the source, writing `path`).
std::vector<std::string> write_deformed_mesh(const std::filesystem::path& path,
                                             const std::filesystem::path& source,
                                             const Eigen::MatrixXd& source_positions, const Mesh& mesh);

// The bytes write_mesh would write.
[[nodiscard]] std::string format_off(const Mesh& mesh);
[[nodiscard]] std::string format_obj(const Mesh& mesh);
[[nodiscard]] std::string format_ply(const Mesh& mesh, PlyEncoding encoding);

}  // namespace pushpull::deform
