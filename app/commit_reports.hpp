// What the review loops do with finished commits, each frame and at the end: record them (and, in a replay,
// hand them to on_commit), and say on stderr what the reviewer must know that the readouts no longer show
// once the drag is over: a commit the solver did not converge for, and one that failed (the model stays as it
// was). Failed commits are recorded as {"record":"commit failed","request":..,"error":..}. Also the undo and
// redo the reviewer asks for: sent, logged, recorded and said, or, with nothing to step to, said and shown.
//
// Thread-safety: the loop's thread.
#pragma once

#include "commit_watch.hpp"
#include "history_steps.hpp"
#include "review_setup.hpp"
#include "session_recorder.hpp"
#include "window_hud.hpp"

#include <functional>
#include <optional>

namespace pushpull::app {

// quiet (a replay, which says each commit its own way): no live reviewer's advice on stderr.
void take_commits(CommitWatch& commits, SessionRecorder& recorder, double t,
                  const std::function<void(const CommitRecord&)>& on_commit,
                  const std::function<void(const FailedCommit&)>& on_failed, bool quiet);

// An undo or redo asked for at time t (the recording's clock): sent to the service, logged ("undo"), recorded
// and, with print, said on stdout; or, when there is nothing to step to (request_history_step), logged
// ("nothing to undo"), said and shown by `notice` from notice_now on (the clock the loop reads it with).
// recorded: a replay's decision, whether the recording sent this step (then the service is not asked).
// Returns whether it was sent.
bool take_history_step(deform::Service& service, HistoryStep step, double t, double notice_now, EventLog& log,
                       SessionRecorder& recorder, TimedNotice& notice, bool print,
                       std::optional<bool> recorded = std::nullopt);

}  // namespace pushpull::app
