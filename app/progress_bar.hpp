// A progress bar on the terminal for long commands (`pushpull replay`): one line on stderr, redrawn in place
// ("[#########-----------]  45%  replaying 12.3 / 27.0 s  commit 2/3"), at most ten times a second. Lines the
// command prints meanwhile go through print(), which clears the bar, prints, and draws it again. Where stderr
// is not a terminal (CI logs, pipes) no bar is drawn: print() is a plain printf to stdout.
// Thread-safety: one thread.
#pragma once

#include <chrono>
#include <string>

namespace pushpull::app {

class ProgressBar {
 public:
  ProgressBar();  // draws only when stderr is a terminal
  ~ProgressBar();  // clears the bar
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // fraction in [0, 1] (clamped); text after the percentage. Redraws when 100 ms passed since the last draw or
  // force is set.
  void update(double fraction, const std::string& text, bool force = false);
  // A line for stdout (without its newline) above the bar.
  void print(const std::string& line);
  // Clears the bar for good (plain output follows); update() draws nothing after it.
  void finish();
  [[nodiscard]] bool drawing() const { return terminal_; }

 private:
  void draw();
  void clear();

  bool terminal_ = false;
  bool drawn_ = false;
  double fraction_ = 0.0;
  std::string text_;
  std::chrono::steady_clock::time_point last_draw_{};
};

// The bar's text line for a fraction and text, `width` cells of '#' and '-' (exposed for the tests).
[[nodiscard]] std::string progress_line(double fraction, const std::string& text, int width = 30);

}  // namespace pushpull::app
