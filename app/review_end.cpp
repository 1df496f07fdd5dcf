#include "review_end.hpp"

#include "commands.hpp"

#include <cstdio>

namespace pushpull::app {

void finish_review(std::optional<std::string>& failure, SessionRecorder& recorder, EventLog& log, double t,
                   const deform::Service& service, const std::string& out, const assets::Model& model,
                   bool print_out) {
  const auto [current, commits] = service.current();  // the state and its index read together
  guarded(failure, [&] {
    nlohmann::json end_fields{{"commits", commits}, {"hash", hash_text(current.hash)}};
    if (failure) end_fields["error"] = *failure;
    recorder.write_record("end", t, end_fields);
    log.write({{"event", "end"},
               {"revision", service.revision()},
               {"hash", hash_text(current.hash)},  // a string: 64 bits lose digits in a JSON double
               {"commits", commits}});
  });
  if (!out.empty()) {
    try {
      write_review_model(out, model, current.state->V);
    } catch (const CommandError& e) {  // the recording still holds the work: say so
      throw CommandError(e.what() + kept_work_note("", recorder));
    }
    if (print_out || failure)
      std::printf("pushpull review: wrote %s (%zu committed push/pull(s))\n", out.c_str(), commits);
  } else if (commits > 0 && print_out) {
    // Without --out the shape lives only in the recording, whose path scrolled past at the start: said.
    if (!recorder.path().empty())
      std::printf(
          "pushpull review: %zu committed push/pull(s) not written to a model file (no --out); the "
          "session is recorded in %s: `pushpull replay %s --out DIR` writes them\n",
          commits, recorder.path().c_str(), recorder.path().c_str());
    else
      std::printf(
          "pushpull review: %zu committed push/pull(s) not written anywhere (no --out, no recording)\n",
          commits);
  }
  if (failure)
    throw CommandError("the review ended on an error: " + *failure + kept_work_note(out, recorder));
}

void finish_review_on_lost_display(const std::function<void()>& wind_down, SessionRecorder& recorder,
                                   EventLog& log, double t, const deform::Service& service,
                                   const std::string& out, const assets::Model& model) {
  std::optional<std::string> failure = "the connection to the X display was lost";
  guarded(failure, wind_down);
  try {
    finish_review(failure, recorder, log, t, service, out, model, /*print_out=*/true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pushpull: error: %s\n", e.what());
  }
}

}  // namespace pushpull::app
