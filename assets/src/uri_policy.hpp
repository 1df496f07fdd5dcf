// URI policy for untrusted glTF files: which buffer/image URIs may be opened.
// Accepted: data: URIs, and relative file paths that stay inside the model's folder.
// Refused: other schemes (http:, file:, ...), absolute paths, drive letters, '..' escaping the
// folder, NUL bytes, malformed percent escapes. Thread-safety: pure functions.
#pragma once

#include <filesystem>
#include <string>

namespace pushpull::assets::detail {

// Empty when `uri` is acceptable; otherwise why it is refused.
std::string uri_problem(const std::string& uri);

bool is_data_uri(const std::string& uri);

// Whether `path` (made canonical, symlinks resolved) lies inside the folder `root_canonical`.
bool path_is_inside(const std::filesystem::path& root_canonical, const std::filesystem::path& path);

}  // namespace pushpull::assets::detail
