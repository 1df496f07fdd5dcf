// Private helpers for the text mesh readers: line-by-line scanning with line numbers, whitespace
// tokenizing and strict number parsing (std::from_chars: no locale, no partial matches).
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace pushpull::deform::detail {

// Walks `text` one line at a time. Lines exclude the '\n' and a trailing '\r'.
class LineCursor {
 public:
  // A UTF-8 byte order mark at the start (editors on Windows write one) is skipped: it is not part of the
  // first line's first word (an OBJ's first "v" read as "\xEF\xBB\xBFv" dropped that vertex and shifted every
  // index). offset() still counts from the text's start.
  explicit LineCursor(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
  }

  // The next line, or false at the end of the text. line_number() is then that line's 1-based number.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  [[nodiscard]] std::size_t line_number() const { return line_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t remaining_bytes() const { return text_.size() - pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Splits one line into whitespace-separated tokens.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : line_(line) {}

  bool next(std::string_view& token) {
    while (pos_ < line_.size() && is_space(line_[pos_])) ++pos_;
    if (pos_ >= line_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !is_space(line_[pos_])) ++pos_;
    token = line_.substr(start, pos_ - start);
    return true;
  }

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
};

// The line up to the first `marker` (a comment), with surrounding whitespace trimmed.
inline std::string_view strip_comment(std::string_view line, char marker) {
  const std::size_t hash = line.find(marker);
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
  while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
  return line;
}

// The whole token must be a number; a leading '+' is accepted.
inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}

inline bool parse_int64(std::string_view token, std::int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && end == token.data() + token.size();
}

}  // namespace pushpull::deform::detail
