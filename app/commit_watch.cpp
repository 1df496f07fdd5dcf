#include "commit_watch.hpp"

namespace pushpull::app {

std::function<void(const std::shared_ptr<const deform::Snapshot>&)> CommitWatch::callback() {
  return [this](const std::shared_ptr<const deform::Snapshot>& s) {
    if (s->kind != deform::Snapshot::Kind::Committed) return;
    const std::uint64_t hash = deform::position_hash(*s->positions);  // ~0.1 ms for 50K vertices
    std::lock_guard lock(mutex_);
    pending_.push_back({++count_, hash, s});
  };
}

std::vector<CommitRecord> CommitWatch::take() {
  std::lock_guard lock(mutex_);
  std::vector<CommitRecord> out;
  out.swap(pending_);
  return out;
}

}  // namespace pushpull::app
