// Choosing vertices for `pushpull deform`: index files and "vertices near a point".
// Errors are CommandError (commands.hpp) naming the file, the line and the problem.
// Thread-safety: free functions without state.
#pragma once

#include <Eigen/Core>

#include <filesystem>
#include <vector>

namespace pushpull::app {

// 0-based vertex indices separated by white space (text after '#' on a line is a comment). Each index must
// lie in [0, vertex_count); duplicates are dropped; the result is sorted. An empty file is an error.
[[nodiscard]] std::vector<int> read_index_file(const std::filesystem::path& path, Eigen::Index vertex_count);

}  // namespace pushpull::app
