// Holds SIGINT, SIGTERM and SIGHUP back while a command writes files that belong together (`pushpull
// deform`'s model and its metrics): a signal in between left a new model beside no metrics, or beside the
// metrics of the run before. Each file is written atomically; with the signal held, the pair is too: a signal
// that arrives is recorded, and acted on (the default action: the process ends with the signal's status) once
// the holder is destroyed, after both are written or the writing failed.
//
// Ownership: installs its handlers for its lifetime and restores the previous ones; one at a time.
// Thread-safety: process-wide handlers (a signal delivered to any thread is held); construct and destroy on
// one thread.
#pragma once

#include <csignal>

namespace pushpull::app {

class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();  // restores the handlers, then raises a held signal (which ends the process)
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  struct sigaction previous_[3]{};
};

}  // namespace pushpull::app
