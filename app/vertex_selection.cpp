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

std::vector<int> read_model_index_file(const std::filesystem::path& path, const assets::Model& model,
                                       std::size_t* unused) {
  const std::string& format = model.report.format;
  if (model.primitives.size() != 1 || (format != "OFF" && format != "OBJ" && format != "PLY"))
    return read_index_file(path, model.deform_mesh.V.rows());
  const std::vector<int>& weld = model.primitives.front().deform_vertex;
  std::vector<int> welded;
  std::size_t left_out = 0;
  for (const int v : read_index_file(path, static_cast<Eigen::Index>(weld.size()))) {
    const int w = weld[static_cast<std::size_t>(v)];
    if (w < 0)
      ++left_out;
    else
      welded.push_back(w);
  }
  if (welded.empty())
    throw CommandError(path.string() + ": every vertex it names is used by no triangle of the model");
  std::sort(welded.begin(), welded.end());
  welded.erase(std::unique(welded.begin(), welded.end()), welded.end());
  if (unused) *unused = left_out;
  return welded;
}

}  // namespace pushpull::app
