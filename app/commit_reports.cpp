#include "commit_reports.hpp"
#include "drag_notes.hpp"
#include "region_notes.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace pushpull::app {

void take_commits(CommitWatch& commits, SessionRecorder& recorder, double t,
                  const std::function<void(const CommitRecord&)>& on_commit,
                  const std::function<void(const FailedCommit&)>& on_failed, bool quiet) {
  for (const CommitRecord& c : commits.take()) {
    recorder.write_commit(t, c);
    const deform::Snapshot& s = *c.snapshot;
    if (!s.converged && !quiet) {
      char estimate[96] = "the solver has no estimate of its distance to the minimiser";
      if (s.error_estimate)
        std::snprintf(estimate, sizeof estimate, "estimated %.1e |d| from the minimiser", *s.error_estimate);
      std::fprintf(
          stderr,
          "pushpull review: commit %zu (%s) is not converged after %d iterations (%s); undo takes it back\n",
          c.index, std::string(deform::method_name(s.method)).c_str(), s.iteration, estimate);
    }
    // What `pushpull deform` and the replay's report say of the same push/pull (a whole part moved, a handle
    // torn out, a steep pull, the solver's own warnings), said here too: the supervisor at the terminal saw
    // none of it. Left out here: the solver's checks of the whole model ("mesh: 83 connected components ...":
    // the same for every commit; `pushpull info` lists them) and its note on how it weighted sliver triangles
    // (nothing for the reviewer to do; METRICS.json and the replay's report keep both).
    if (!quiet) {
      std::vector<std::string> warnings;
      for (const std::string& w : s.warnings)
        if (w.rfind("mesh: ", 0) != 0 && w.rfind("deformer: the region has sliver triangles", 0) != 0)
          warnings.push_back(w);
      if (s.region)
        if (const std::optional<UnheldRegion> unheld = unheld_region(*s.region))
          warnings.insert(warnings.begin(), unheld_region_text(*unheld));
      if (s.committed_request)
        if (const auto* handle = std::get_if<deform::SurfaceHandle>(&s.committed_request->handle))
          if (const auto steep = steep_pull_warning(s.d.norm(), handle->radius))
            warnings.insert(warnings.begin(), *steep);
      for (const std::string& w : warnings)
        std::fprintf(stderr, "pushpull review: commit %zu: warning: %s\n", c.index, w.c_str());
    }
    if (on_commit) on_commit(c);
  }
  for (const FailedCommit& f : commits.take_failed()) {
    if (!quiet)
      std::fprintf(stderr,
                   "pushpull review: the push/pull was not committed (the model stays as it was): %s\n",
                   f.error.c_str());
    recorder.write_record("commit failed", t, {{"request", f.request}, {"error", f.error}});
    if (on_failed) on_failed(f);
  }
}

bool take_history_step(deform::Service& service, HistoryStep step, double t, double notice_now, EventLog& log,
                       SessionRecorder& recorder, TimedNotice& notice, bool print,
                       std::optional<bool> recorded) {
  const char* name = step == HistoryStep::Undo ? "undo" : "redo";
  if (recorded && *recorded) send_history_step(service, step);
  if (recorded ? *recorded : request_history_step(service, step)) {
    log.write({{"event", name}});
    recorder.write_record(name, t);
    if (print) std::printf("pushpull review: %s\n", name);
    return true;
  }
  announce(notice, nothing_to(step), notice_now, print);
  log.write({{"event", nothing_to(step)}});
  return false;
}

}  // namespace pushpull::app
