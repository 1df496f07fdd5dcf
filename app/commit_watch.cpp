#include "commit_watch.hpp"

namespace pushpull::app {

std::function<void(const std::shared_ptr<const deform::Snapshot>&)> CommitWatch::callback() {
  return [this](const std::shared_ptr<const deform::Snapshot>& s) {
    // Snapshots arrive in publication order on the worker: every one carries the committed state it belongs
    // to, so the state before a commit is the rest of the snapshot published before it.
    std::shared_ptr<const deform::Mesh> before = current_;
    current_ = s->rest;
    if (s->kind == deform::Snapshot::Kind::Error && !s->failed_commit)
      return;  // a preview's: not the commit's
    if (s->kind == deform::Snapshot::Kind::Error) {
      std::lock_guard lock(mutex_);
      if (expected_.erase(s->request) > 0) {
        failed_.push_back({s->request, s->error});
      } else {
        recent_errors_[s->request] = s->error;
        if (recent_errors_.size() > 64) recent_errors_.erase(recent_errors_.begin());  // the oldest request
      }
      return;
    }
    if (s->kind != deform::Snapshot::Kind::Committed) return;
    const std::uint64_t hash = deform::position_hash(*s->positions);  // ~0.1 ms for 50K vertices
    std::lock_guard lock(mutex_);
    expected_.erase(s->request);
    pending_.push_back({++count_, hash, s, std::move(before)});
  };
}

void CommitWatch::expect_commit(std::uint64_t request) {
  std::lock_guard lock(mutex_);
  if (const auto it = recent_errors_.find(request); it != recent_errors_.end()) {
    failed_.push_back({request, it->second});  // it failed before the loop got here
    recent_errors_.erase(it);
  } else {
    expected_.insert(request);
  }
}

std::vector<FailedCommit> CommitWatch::take_failed() {
  std::lock_guard lock(mutex_);
  std::vector<FailedCommit> out;
  out.swap(failed_);
  return out;
}

std::vector<CommitRecord> CommitWatch::take() {
  std::lock_guard lock(mutex_);
  std::vector<CommitRecord> out;
  out.swap(pending_);
  return out;
}

}  // namespace pushpull::app
