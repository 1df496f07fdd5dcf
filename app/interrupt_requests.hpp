// Ctrl-C (SIGINT) and SIGTERM during a review end it the way Esc does: the loop sees the request at its next
// frame and ends normally, so the committed work is written to --out and the recording gets its end record.
// A second signal while the first is being handled ends the process at once (the default action), after a
// line on stderr saying that what was not yet written is lost, and how the recording rebuilds it.
//
// Ownership: an InterruptRequests installs the handlers for its lifetime and restores the previous ones; one
// at a time. Thread-safety: the handler sets a lock-free atomic flag (the second signal's writes its line);
// requested() may be read from any thread.
#pragma once

#include <csignal>

namespace pushpull::app {

class InterruptRequests {
 public:
  InterruptRequests();
  ~InterruptRequests();
  InterruptRequests(const InterruptRequests&) = delete;
  InterruptRequests& operator=(const InterruptRequests&) = delete;

  // Whether SIGINT or SIGTERM arrived since construction.
  [[nodiscard]] bool requested() const;

 private:
  struct sigaction previous_int_ {
  }, previous_term_{};
};

}  // namespace pushpull::app
