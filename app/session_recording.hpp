// Reading a session recording (session_recorder.hpp) for `pushpull replay`: the header, the derived records
// (press, release, commit with its hash, undo, redo, method, press held, end) and the input script for xr/sim,
// checked line by line (method and press held records also steer the replay).
//
// Errors (CommandError, "FILE:LINE: problem"): a line that is not a JSON object, or a broken input line, in the
// middle of the file (corrupted); a first line that is not a header. A recording cut short (the session crashed
// or the file was truncated: a last line without its newline that does not parse, or no "end" record) is not an
// error: what precedes the cut is replayed and `cut` says where and why.
// Thread-safety: plain values.
#pragma once

#include "head_anchor.hpp"
#include "press_hold.hpp"
#include "size_change.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

struct RecordedCommit {
  std::size_t line = 0;  // 1-based line in the recording
  nlohmann::json record;  // {"record":"commit","index":..,"hash":"0x..","d":[..],...}
};

struct SessionRecording {
  std::string path;
  nlohmann::json header;                     // line 1
  int format_version = 0;  // N of the header's "pushpull-session-N"; 0 when it says something else
  std::vector<nlohmann::json> records;       // every derived record, in order, with "line" added
  std::vector<RecordedCommit> commits;       // the commit records, in commit order
  std::vector<std::pair<double, std::string>> method_changes;  // "method" records: (time s, method name), in order
  std::vector<std::pair<double, std::string>>
      colour_changes;                        // "colour" records: (time s, colour map), in order
  std::vector<SizeChange> size_changes;      // "sizes" records, in order
  std::vector<std::pair<double, std::string>> history_steps;  // "undo"/"redo" records: (time s, kind)
  std::vector<double> cancels;                                // "cancel" records: time s, in order
  std::vector<PressHold> press_holds;        // "press held" records, in order
  std::optional<HeadAnchor> anchor;          // the "anchor" record, if any (at most one)
  std::string script;                        // the complete lines before any cut, '\n'-terminated (for xr/sim)
  double last_input_time = 0.0;              // largest "t" of an input line (seconds)
  // The runtime's exit as the review recorded it (xr/sim's "exit" event line), if any: the session ends
  // there.
  std::optional<double> exit_time;
  double rate_hz = 0.0;                      // display rate of the recorded session (0: unknown)
  std::string profile;                       // the interaction profile the runtime chose ("" when none)
  std::size_t lines = 0;                     // complete lines read
  std::optional<std::string> cut;            // set when the recording stops early: where and why
};

// Reads and checks `path`; throws CommandError naming the file (and the line) and the problem.
[[nodiscard]] SessionRecording read_session_recording(const std::string& path);

// What each committed release of the recording became, in release order: its commit (the position in
// `recording.commits` of the commit record with the release's request), or none (the commit failed, or had
// not landed when the recording ended). Releases without a request number are left out.
[[nodiscard]] std::vector<std::optional<std::size_t>> release_outcomes(const SessionRecording& recording);

// What the recorded session's undo and redo made of its commits: the commits (their "index", 1-based) the
// final model is made of, in order, and the session's history as text ("push/pull 1, push/pull 2, undo,
// redo"). Replays the recorded order of commits issued (committed releases whose commit landed), undos and
// redos on a history as deform::Service keeps it (a commit after an undo drops the undone states).
struct CommitHistory {
  std::vector<std::size_t> kept;
  std::vector<std::string> steps;
};
[[nodiscard]] CommitHistory commit_history(const SessionRecording& recording);

}  // namespace pushpull::app
