#include "uri_policy.hpp"

#include <cctype>
#include <system_error>

namespace pushpull::assets::detail {

namespace {

bool has_scheme(const std::string& uri) {
  // RFC 3986: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (char c : uri) {
    if (c == ':') return true;
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

bool is_data_uri(const std::string& uri) {
  if (uri.size() < 5) return false;
  std::string head = uri.substr(0, 5);
  for (char& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return head == "data:";
}

std::string uri_problem(const std::string& uri) {
  if (uri.empty()) return "empty uri";
  if (is_data_uri(uri)) return {};
  if (has_scheme(uri))
    return "uri scheme '" + uri.substr(0, uri.find(':')) +
           ":' is not allowed (only data: and relative file paths)";
  // Percent-decode, then judge the path that a file system would see.
  std::string path;
  path.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%') {
      if (i + 2 >= uri.size()) return "malformed percent escape";
      const int hi = hex_value(uri[i + 1]);
      const int lo = hex_value(uri[i + 2]);
      if (hi < 0 || lo < 0) return "malformed percent escape";
      path.push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else {
      path.push_back(uri[i]);
    }
  }
  if (path.find('\0') != std::string::npos) return "uri contains a NUL byte";
  if (path.front() == '/' || path.front() == '\\') return "absolute paths are not allowed";
  if (path.size() >= 2 && std::isalpha(static_cast<unsigned char>(path[0])) && path[1] == ':')
    return "absolute paths are not allowed";
  if (path.find('?') != std::string::npos || path.find('#') != std::string::npos)
    return "query or fragment in a file uri";
  int depth = 0;
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find_first_of("/\\", start);
    if (end == std::string::npos) end = path.size();
    const std::string part = path.substr(start, end - start);
    if (part == "..") {
      if (--depth < 0) return "points outside the model's folder ('..')";
    } else if (!part.empty() && part != ".") {
      ++depth;
    }
    start = end + 1;
  }
  return {};
}

bool path_is_inside(const std::filesystem::path& root_canonical, const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  if (ec) return false;
  auto r = root_canonical.begin();
  auto q = p.begin();
  for (; r != root_canonical.end(); ++r, ++q) {
    if (r->empty()) continue;  // trailing separator
    if (q == p.end() || *q != *r) return false;
  }
  return true;
}

}  // namespace pushpull::assets::detail
