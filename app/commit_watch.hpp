// Hands the deformation service's commits from its worker to the frame loop: ServiceOptions::on_publish
// pushes every Committed snapshot here (worker thread), the loop takes them in commit order (its thread)
// to record their hashes and, in a replay, to write the results.
// Thread-safety: publish() and take() may run on different threads (one mutex, held only to move pointers).
#pragma once

#include "pushpull/deform/service.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace pushpull::app {

struct CommitRecord {
  std::size_t index = 0;   // 1, 2, ... in commit order within the session
  std::uint64_t hash = 0;  // deform::position_hash of the committed positions (the history entry's hash)
  std::shared_ptr<const deform::Snapshot> snapshot;  // kind Committed; rest and positions = the new state
  // The committed state the commit was computed from (the rest of the snapshots published before it); null
  // when no snapshot was seen before it (then it is the service's initial mesh).
  std::shared_ptr<const deform::Mesh> before;
};

class CommitWatch {
 public:
  // For ServiceOptions::on_publish; the watch must outlive the service.
  [[nodiscard]] std::function<void(const std::shared_ptr<const deform::Snapshot>&)> callback();
  // The commits published since the last call, oldest first.
  [[nodiscard]] std::vector<CommitRecord> take();

 private:
  std::mutex mutex_;
  std::vector<CommitRecord> pending_;
  std::size_t count_ = 0;
  std::shared_ptr<const deform::Mesh> current_;  // the committed state of the last snapshot seen (worker only)
};

}  // namespace pushpull::app
