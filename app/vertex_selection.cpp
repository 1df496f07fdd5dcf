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
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw CommandError(path.string() + ": is a folder, not an index file");
  std::ifstream in(path);
  if (!in) throw CommandError(path.string() + ": cannot open index file: " + std::strerror(errno));
  std::vector<int> indices;
  std::string line;
  for (std::size_t line_no = 1; std::getline(in, line); ++line_no) {
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 byte order mark
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      long long value = 0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
      const std::string where = path.string() + ":" + std::to_string(line_no) + ": ";
      if (ec != std::errc{} || end != token.data() + token.size()) {
        // (A damaged file's control bytes, NUL among them, are not sent to the terminal.)
        for (char& c : token)
          if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
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

bool index_files_name_file_vertices(const assets::Model& model) {
  const std::string& format = model.report.format;
  return model.primitives.size() == 1 && (format == "OFF" || format == "OBJ" || format == "PLY");
}

std::vector<int> read_model_index_file(const std::filesystem::path& path, const assets::Model& model,
                                       std::size_t* unused, std::vector<int>* named) {
  if (!index_files_name_file_vertices(model)) {
    std::vector<int> indices = read_index_file(path, model.deform_mesh.V.rows());
    if (named) *named = indices;
    return indices;
  }
  const std::vector<int>& weld = model.primitives.front().deform_vertex;
  std::vector<int> welded;
  std::size_t left_out = 0;
  const std::vector<int> file_vertices = read_index_file(path, static_cast<Eigen::Index>(weld.size()));
  for (const int v : file_vertices) {
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
  if (named) *named = file_vertices;
  return welded;
}

namespace {

// "3", "3 and 7", "3, 7 and 9".
std::string joined(const std::vector<int>& numbers) {
  std::string text;
  for (std::size_t k = 0; k < numbers.size(); ++k)
    text += (k == 0 ? "" : k + 1 == numbers.size() ? " and " : ", ") + std::to_string(numbers[k]);
  return text;
}

std::string vertices_text(const std::vector<int>& numbers) {
  return (numbers.size() == 1 ? "vertex " : "vertices ") + joined(numbers);
}

}  // namespace

std::string shared_vertex_message(const assets::Model& model, const std::vector<int>& both,
                                  const SelectionSource& handle, const SelectionSource& fixed) {
  const int welded = both.front();
  const std::string count = both.size() == 1 ? "" : " (" + std::to_string(both.size()) + " such points)";
  const std::string ending = count + "; a vertex cannot be both held and pulled";
  if (!index_files_name_file_vertices(model))
    return "region of interest: vertex " + std::to_string(welded) + " is both a handle and a fixed vertex" +
           ending;
  // The file's vertices that are this point, and which of them each index file lists.
  const std::vector<int>& weld = model.primitives.front().deform_vertex;
  auto listed_in = [&](const SelectionSource& source) {
    std::vector<int> listed;
    for (const int v : source.file_vertices)
      if (v >= 0 && static_cast<std::size_t>(v) < weld.size() && weld[static_cast<std::size_t>(v)] == welded)
        listed.push_back(v);
    std::sort(listed.begin(), listed.end());
    return listed;
  };
  const std::vector<int> in_handle = listed_in(handle), in_fixed = listed_in(fixed);
  std::vector<int> in_both;
  std::set_intersection(in_handle.begin(), in_handle.end(), in_fixed.begin(), in_fixed.end(),
                        std::back_inserter(in_both));
  const bool one = in_both.size() == 1;
  if (!in_both.empty())
    return "region of interest: file " + vertices_text(in_both) + (one ? " is" : " are") + " in both " +
           handle.path + " and " + fixed.path + ending;
  if (handle.path.empty())  // the handle was picked around a point (--handle-at)
    return "region of interest: file " + vertices_text(in_fixed) + " of " + fixed.path +
           (in_fixed.size() == 1 ? " lies" : " lie") + " in the handle picked around --handle-at" + ending;
  return "region of interest: file " + vertices_text(in_handle) + " of " + handle.path + " and " +
         vertices_text(in_fixed) + " of " + fixed.path + " are one point once the seams are welded" + ending;
}

}  // namespace pushpull::app
