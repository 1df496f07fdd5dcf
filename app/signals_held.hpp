// Holds SIGINT, SIGTERM and SIGHUP back while a command writes files that belong together (`pushpull
// deform`'s model and its metrics): a signal in between left a new model beside no metrics, or beside the
// metrics of the run before. Each file is written atomically; with the signal held, the pair is too: the
// first signal that arrives is recorded and acted on once the holder is destroyed, after both are written, by
// raising it again under the handler that was there before (the default one ends the process with the
// signal's status; one the shell set to ignore, as nohup does for SIGHUP, still ignores it). A second signal
// while one is held is acted on at once (a write that hangs can still be interrupted).
//
// When the holder is destroyed by an exception (a write failed), the held signal is not raised there, so the
// command's error can still be said: raise_held_signal() then raises it, after the error is printed.
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
  // Restores the handlers, then raises a held signal, unless an exception is unwinding the stack (then it
  // stays pending for raise_held_signal()).
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  struct sigaction previous_[3]{};
  int exceptions_ = 0;  // std::uncaught_exceptions() at construction
};

// Raises the signal a SignalsHeld destroyed by an exception left pending, if any (call after saying the
// error).
void raise_held_signal();

}  // namespace pushpull::app
