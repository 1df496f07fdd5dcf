// Index files and radius picks for `pushpull deform`.
#include "vertex_selection.hpp"

#include "commands.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

namespace pushpull::app {

std::vector<int> read_index_file(const std::filesystem::path& path, Eigen::Index vertex_count) {
  std::ifstream in(path);
  if (!in) throw CommandError(path.string() + ": cannot open index file: " + std::strerror(errno));
  std::vector<int> indices;
  std::string line;
  for (std::size_t line_no = 1; std::getline(in, line); ++line_no) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      long long value = 0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
      const std::string where = path.string() + ":" + std::to_string(line_no) + ": ";
      if (ec != std::errc{} || end != token.data() + token.size()) {
        throw CommandError(where + "'" + token + "' is not a vertex index (expected a 0-based integer)");
      }
      if (value < 0 || value >= vertex_count) {
        throw CommandError(where + "vertex index " + token + " out of range (the mesh has " +
                           std::to_string(vertex_count) + " vertices, indices are 0-based)");
      }
      indices.push_back(static_cast<int>(value));
    }
  }
  if (in.bad()) throw CommandError(path.string() + ": read error");
  if (indices.empty()) throw CommandError(path.string() + ": no vertex indices in the file");
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

}  // namespace pushpull::app
