// `pushpull replay --compare asan,arap-sr`: the same recording replayed once per method (each a `pushpull replay
// --method M --out OUT/M` run of this executable, so each has its own simulated runtime), then OUT/compare.html
// with the methods side by side per push/pull: displacement and curvature-sign pictures, |d|, iterations,
// sign reversals, displacement along and across d (read back from each run's metrics JSON).
// Thread-safety: runs on the calling thread.
#pragma once

#include "replay_session.hpp"

#include <string>
#include <vector>

namespace pushpull::app {

// Throws CommandError naming the method whose replay failed (its output says why) or the file not written.
void run_replay_comparison(const ReplayOptions& options, const std::vector<std::string>& methods);

}  // namespace pushpull::app
