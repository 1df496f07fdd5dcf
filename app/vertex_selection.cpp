// Index files and radius picks for `pushpull deform`.
#include "vertex_selection.hpp"

#include "commands.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
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

namespace {

// Whether the model's index files name the file's own vertices (read_model_index_file).
bool numbered_by_file(const assets::Model& model) {
  const std::string& format = model.report.format;
  return model.primitives.size() == 1 && (format == "OFF" || format == "OBJ" || format == "PLY");
}

std::string joined(const std::vector<int>& numbers) {
  std::string text;
  for (std::size_t k = 0; k < numbers.size(); ++k)
    text += (k == 0 ? "" : k + 1 == numbers.size() ? " and " : ", ") + std::to_string(numbers[k]);
  return text;
}

}  // namespace

std::string shared_vertex_message(const assets::Model& model, const std::vector<int>& both,
                                  const std::string& handle_file, const std::string& fixed_file) {
  const int welded = both.front();
  const std::string count = both.size() == 1 ? "" : " (" + std::to_string(both.size()) + " such points)";
  if (!numbered_by_file(model))
    return "region of interest: vertex " + std::to_string(welded) + " is both a handle and a fixed vertex" +
           count;
  // The file's vertices that are this point, and which of them each index file lists.
  const std::vector<int>& weld = model.primitives.front().deform_vertex;
  std::vector<int> file_vertices;
  for (std::size_t v = 0; v < weld.size(); ++v)
    if (weld[v] == welded) file_vertices.push_back(static_cast<int>(v));
  auto listed_in = [&](const std::string& file) {
    std::vector<int> listed;
    if (file.empty()) return listed;
    const std::vector<int> named = read_index_file(file, static_cast<Eigen::Index>(weld.size()));
    std::set_intersection(named.begin(), named.end(), file_vertices.begin(), file_vertices.end(),
                          std::back_inserter(listed));
    return listed;
  };
  const std::vector<int> in_handle = listed_in(handle_file), in_fixed = listed_in(fixed_file);
  auto vertices = [](const std::vector<int>& v) {
    return (v.size() == 1 ? "vertex " : "vertices ") + joined(v);
  };
  auto is_are = [](const std::vector<int>& v) { return v.size() == 1 ? " is" : " are"; };
  std::string text = "region of interest: file ";
  if (in_handle.empty() || in_fixed.empty())  // one set was not read from a file (--handle-at)
    text += vertices(file_vertices) + is_are(file_vertices) + " both a handle and a fixed vertex";
  else if (in_handle == in_fixed)
    text += vertices(in_handle) + is_are(in_handle) + " in both " + handle_file + " and " + fixed_file;
  else
    text += "vertices " + joined(in_handle) + " (" + handle_file + ") and " + joined(in_fixed) + " (" +
            fixed_file + ") are one point once the seams are welded";
  return text + count + "; a vertex cannot be both held and pulled";
}

}  // namespace pushpull::app
