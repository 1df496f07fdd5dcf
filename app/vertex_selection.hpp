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

// An index file for `model`, as the commands read one: an OFF/OBJ/PLY model's files name the vertices of the
// file itself (its own numbering, whatever the weld merged), a glTF/GLB/Draco model's the vertices of its
// welded surface (model.deform_mesh, as `pushpull info` counts them). Returns the welded surface's vertices
// named (sorted, unique). File vertices that no triangle uses are not on the surface: left out, counted in
// *unused (an error when nothing else is left).
[[nodiscard]] std::vector<int> read_model_index_file(const std::filesystem::path& path,
                                                     const assets::Model& model,
                                                     std::size_t* unused = nullptr);

// The message for welded surface vertices `both` (sorted, not empty) that are both a handle and a fixed
// vertex, naming the first as the user numbered it: for an OFF/OBJ/PLY model, the file's vertices the weld
// made that point (and which index file lists which), else the welded surface's number. handle_file and
// fixed_file: the index files the sets came from (empty: not from a file).
[[nodiscard]] std::string shared_vertex_message(const assets::Model& model, const std::vector<int>& both,
                                                const std::string& handle_file,
                                                const std::string& fixed_file);

}  // namespace pushpull::app
