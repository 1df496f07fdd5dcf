// `pushpull replay`: a recorded review session (session_recorder.hpp) run again through the same review loop
// (review_loop.hpp), headless, against the simulated OpenXR runtime (xr/sim) with the recording as its input
// script on the virtual clock, and lavapipe where no Vulkan driver is named.
//
// Writes into `out`: input.jsonl (the script given to xr/sim), replay-session.jsonl (the replay's own
// recording), commit-NN.<ext> after every commit and final.<ext> at the end (.glb for glTF models, else the
// model's own mesh format), commit-NN-before.<ext>, commit-NN.metrics.json (metrics_json.hpp), eyes/ (both
// eyes one frame after each release and at the end, from xr/sim's capture; only those frames are drawn, each
// after the solver settled, so they are the same on every run; --capture-every N draws and keeps every Nth
// frame too), commit-NN-*.png (before, after, displacement and curvature-sign pictures drawn as `pushpull
// render` draws them, by one renderer for the whole report: render_session.hpp), report.html.
//
// Checks: each replayed commit is paired with a recorded one by release order (every released push/pull ends
// as a commit or a failed commit, in the recording as in the replay). Its hash (deform::position_hash over
// the committed positions) must be bit-identical to the recorded one when it was solved with the method that
// commit was made with (a session may switch methods) and the recorded mu; with another --method or --mu the
// positions differ by design and hashes are not compared, but its d must equal the recorded one within 1e-9
// model units (the same input gave the same push/pull). Every recorded commit must be reproduced, and as many
// push/pulls as recorded must fail to commit; with another --method or --mu a push/pull it cannot commit is
// said and reported instead. Desktop-mode recordings are checked the same way (the desktop loop feeds its
// mouse gesture through the float aim pose it records). The first mismatch makes the command fail, naming it
// (after the outputs are written). Thread-safety: runs on the calling thread (sets process environment
// variables for the runtime).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace pushpull::app {

struct ReplayOptions {
  std::string recording;
  std::string out;
  std::string model;                // "" = the header's model path
  std::string method;               // "" = the recorded method
  std::optional<double> mu;         // none = the recorded mu
  std::vector<int> eye_size{256, 256};
  std::vector<int> picture_size{480, 360};
  int capture_every = 0;  // also both eyes every N frames (0: only at each release and at the end)
  bool pictures = true;   // the report's per-commit pictures (four per commit)
};

// Throws CommandError naming the file and the problem: unreadable or corrupted recording (with its line),
// model SHA-256 different from the recording's, a commit that does not match.
void run_replay(const ReplayOptions& options);

}  // namespace pushpull::app
