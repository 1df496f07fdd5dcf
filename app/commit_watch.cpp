#include "commit_watch.hpp"

namespace pushpull::app {

std::function<void(const std::shared_ptr<const deform::Snapshot>&)> CommitWatch::callback() {
  return [this](const std::shared_ptr<const deform::Snapshot>& s) {
    // Snapshots arrive in publication order on the worker: every one carries the committed state it belongs
    // to, so the state before a commit is the rest of the snapshot published before it.
    std::shared_ptr<const deform::Mesh> before = current_;
    current_ = s->rest;
    if (s->kind != deform::Snapshot::Kind::Committed) return;
    const std::uint64_t hash = deform::position_hash(*s->positions);  // ~0.1 ms for 50K vertices
    std::lock_guard lock(mutex_);
    pending_.push_back({++count_, hash, s, std::move(before)});
  };
}

std::vector<CommitRecord> CommitWatch::take() {
  std::lock_guard lock(mutex_);
  std::vector<CommitRecord> out;
  out.swap(pending_);
  return out;
}

}  // namespace pushpull::app
