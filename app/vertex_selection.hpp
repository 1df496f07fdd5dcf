// Choosing vertices for `pushpull deform`: index files and "vertices near a point".
// Errors are CommandError (commands.hpp) naming the file, the line and the problem.
// Thread-safety: free functions without state.
#pragma once

#include "pushpull/assets/model.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace pushpull::app {

// 0-based vertex indices separated by white space (text after '#' on a line is a comment). Each index must
// lie in [0, vertex_count); duplicates are dropped; the result is sorted. An empty file is an error.
[[nodiscard]] std::vector<int> read_index_file(const std::filesystem::path& path, Eigen::Index vertex_count);

// Whether the index files of `model` name the vertices of its file (an OFF/OBJ/PLY: its own numbering,
// whatever the weld merged) rather than its welded surface's (a glTF/GLB/Draco, as `pushpull info` counts
// them).
[[nodiscard]] bool index_files_name_file_vertices(const assets::Model& model);

// An index file for `model`, as the commands read one (index_files_name_file_vertices says how it numbers
// vertices). Returns the welded surface's vertices named (sorted, unique). File vertices that no triangle
// uses are not on the surface: left out, counted in *unused (an error when nothing else is left). *named,
// when given, receives the numbers as the file wrote them (sorted, unique).
[[nodiscard]] std::vector<int> read_model_index_file(const std::filesystem::path& path,
                                                     const assets::Model& model,
                                                     std::size_t* unused = nullptr,
                                                     std::vector<int>* named = nullptr);

// Where a set of vertices came from: an index file (its path and the numbers it wrote), or not (empty path:
// picked around a point).
struct SelectionSource {
  std::string path;
  std::vector<int> file_vertices;
};

// The message for welded surface vertices `both` (sorted, not empty) that are both a handle and a fixed
// vertex, naming the first as the user numbered it: for an OFF/OBJ/PLY model, the file's vertices that are
// that point and which index file lists which, else the welded surface's number.
[[nodiscard]] std::string shared_vertex_message(const assets::Model& model, const std::vector<int>& both,
                                                const SelectionSource& handle, const SelectionSource& fixed);

}  // namespace pushpull::app
