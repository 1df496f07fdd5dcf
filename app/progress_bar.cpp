#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pushpull::app {

std::string progress_line(double fraction, const std::string& text, int width) {
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int filled = int(std::floor(f * width + 1e-9));
  char percent[16];
  std::snprintf(percent, sizeof percent, "%4d%%", int(std::floor(f * 100.0 + 1e-9)));
  std::string line;
  line.reserve(size_t(width) + text.size() + 16);
  line += '[';
  line.append(size_t(filled), '#');
  line.append(size_t(width - filled), '-');
  line += "] ";
  line += percent;
  if (!text.empty()) {
    line += "  ";
    line += text;
  }
  return line;
}

ProgressBar::ProgressBar() : terminal_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() { clear(); }

void ProgressBar::finish() {
  clear();
  terminal_ = false;
}

void ProgressBar::update(double fraction, const std::string& text, bool force) {
  fraction_ = fraction;
  text_ = text;
  if (!terminal_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw();
}

void ProgressBar::print(const std::string& line) {
  clear();
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
  if (terminal_) draw();
}

void ProgressBar::draw() {
  std::fprintf(stderr, "\r\033[K%s", progress_line(fraction_, text_).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace pushpull::app
