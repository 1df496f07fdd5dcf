// Hands the deformation service's commits from its worker to the frame loop: ServiceOptions::on_publish
// pushes every Committed snapshot here (worker thread), the loop takes them in commit order (its thread)
// to record their hashes and, in a replay, to write the results.
// Thread-safety: publish() and take() may run on different threads (one mutex, held only to move pointers).
#pragma once

#include "pushpull/deform/service.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
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

// A commit the service could not make (its solve threw, or its request was stale): the model stays as it was.
struct FailedCommit {
  std::uint64_t request = 0;  // Service::commit's sequence
  std::string error;          // the service's message
};

class CommitWatch {
 public:
  // For ServiceOptions::on_publish; the watch must outlive the service.
  [[nodiscard]] std::function<void(const std::shared_ptr<const deform::Snapshot>&)> callback();
  // The loop committed `request` (Service::commit's sequence): a commit error published for it
  // (Snapshot::failed_commit) is a failed commit; a preview's error for the same request is not.
  void expect_commit(std::uint64_t request);
  // The commits published since the last call, oldest first.
  [[nodiscard]] std::vector<CommitRecord> take();
  // The expected commits that failed since the last call, oldest first.
  [[nodiscard]] std::vector<FailedCommit> take_failed();

 private:
  std::mutex mutex_;
  std::vector<CommitRecord> pending_;
  std::set<std::uint64_t> expected_;  // committed requests not yet finished
  std::vector<FailedCommit> failed_;
  // The last commit errors by request: one may be published before the loop says it committed that request.
  std::map<std::uint64_t, std::string> recent_errors_;
  std::size_t count_ = 0;
  std::shared_ptr<const deform::Mesh> current_;  // the committed state of the last snapshot seen (worker only)
};

}  // namespace pushpull::app
