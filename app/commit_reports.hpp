// What the review loops do with finished commits, each frame and at the end: record them (and, in a replay,
// hand them to on_commit), and say on stderr what the reviewer must know that the readouts no longer show
// once the drag is over: a commit the solver did not converge for, and one that failed (the model stays as it
// was). Failed commits are recorded as {"record":"commit failed","request":..,"error":..}.
//
// Thread-safety: the loop's thread.
#pragma once

#include "commit_watch.hpp"
#include "session_recorder.hpp"

#include <functional>

namespace pushpull::app {

void take_commits(CommitWatch& commits, SessionRecorder& recorder, double t,
                  const std::function<void(const CommitRecord&)>& on_commit);

}  // namespace pushpull::app
