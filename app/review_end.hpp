// The end of a review (headset or desktop loop), also after an error in the loop: the committed work is never
// lost to a second error on the way out (a full disk under the recording, a lost GPU device while waiting).
//
// Each loop keeps its failure as std::optional<std::string> (the message of the first error; none: a normal
// end), runs the steps of its shutdown through guarded(), waits for the deformation service, then calls
// finish_review(), which writes the recording's end record and the log's end event, then --out, then throws
// CommandError for the failure, saying where the committed work is.
//
// Thread-safety: the loop's thread.
#pragma once

#include "review_setup.hpp"
#include "session_recorder.hpp"

#include "pushpull/deform/service.hpp"

#include <exception>
#include <functional>
#include <optional>
#include <string>

namespace pushpull::app {

// Runs step(); an exception it throws becomes `failure` (the first one is kept) instead of escaping.
template <class Step>
void guarded(std::optional<std::string>& failure, Step&& step) {
  try {
    step();
  } catch (const std::exception& e) {
    if (!failure) failure = e.what();
  }
}

// With the service idle and its commits taken: the "end" record at recording time t (commits, hash, and the
// error if any) and the log's end event (both guarded), then the committed model to `out` (if set; printed
// when print_out or after a failure), then CommandError for the failure. Throws what write_review_model
// throws.
void finish_review(std::optional<std::string>& failure, SessionRecorder& recorder, EventLog& log, double t,
                   const deform::Service& service, const std::string& out, const assets::Model& model,
                   bool print_out);

// The last words of a review whose window's X display connection broke (MirrorWindow::on_connection_lost:
// the process ends right after): `wind_down` (cancel the drag in progress, wait for the service, take its
// commits; guarded), then finish_review with that failure, whose message (where the work is) is printed on
// stderr instead of thrown.
void finish_review_on_lost_display(const std::function<void()>& wind_down, SessionRecorder& recorder,
                                   EventLog& log, double t, const deform::Service& service,
                                   const std::string& out, const assets::Model& model);

}  // namespace pushpull::app
