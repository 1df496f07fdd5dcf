#include "pushpull/renderer/vertex_stream.hpp"

#include <stdexcept>

namespace pushpull::renderer {

VertexStream::Lease& VertexStream::Lease::operator=(Lease&& other) noexcept {
  if (this != &other) {
    reset();
    stream_ = std::move(other.stream_);
    set_ = other.set_;
    other.stream_.reset();
  }
  return *this;
}

void VertexStream::Lease::reset() {
  if (stream_) stream_->give_back(set_);
  stream_.reset();
}

std::span<float> VertexStream::Lease::positions() const {
  const size_t v = stream_->vertex_count_;
  return {stream_->sets_[set_].base, 3 * v};
}

std::span<float> VertexStream::Lease::normals() const {
  const size_t v = stream_->vertex_count_;
  return {stream_->sets_[set_].base + 3 * v, 3 * v};
}

std::span<float> VertexStream::Lease::scalars() const {
  const size_t v = stream_->vertex_count_;
  return {stream_->sets_[set_].base + 6 * v, v};
}

VertexStream::VertexStream(uint32_t vertex_count, std::vector<float*> bases) : vertex_count_(vertex_count) {
  for (float* base : bases) sets_.push_back({base, State::free, 0});
}

VertexStream::Lease VertexStream::acquire() {
  std::lock_guard lock(mutex_);
  for (uint32_t i = 0; i < sets_.size(); ++i)
    if (sets_[i].state == State::free) {
      sets_[i].state = State::writing;
      Lease lease;
      lease.stream_ = shared_from_this();
      lease.set_ = i;
      return lease;
    }
  return {};
}

void VertexStream::publish(Lease&& lease) {
  if (!lease || lease.stream_.get() != this)
    throw std::invalid_argument("VertexStream::publish: not a lease of this stream");
  std::lock_guard lock(mutex_);
  if (published_ >= 0) sets_[size_t(published_)].state = State::free;  // never drawn
  published_ = int(lease.set_);
  sets_[lease.set_].state = State::published;
  lease.stream_.reset();  // published: not given back
}

void VertexStream::give_back(uint32_t set) {
  std::lock_guard lock(mutex_);
  sets_[set].state = State::free;
}

void VertexStream::retire_current(uint64_t frame) {
  if (current_ < 0) return;
  Set& s = sets_[size_t(current_)];
  s.state = State::retiring;
  s.last_frame = frame == 0 ? 0 : frame - 1;  // drawn by frames before `frame` at most
  current_ = -1;
}

int VertexStream::begin_frame(uint64_t frame, uint64_t frames_finished) {
  std::lock_guard lock(mutex_);
  for (Set& s : sets_)
    if (s.state == State::retiring && s.last_frame < frames_finished) s.state = State::free;
  if (published_ >= 0) {
    retire_current(frame);
    current_ = published_;
    sets_[size_t(current_)].state = State::current;
    published_ = -1;
  }
  return current_;
}

void VertexStream::detach(uint64_t frame) {
  std::lock_guard lock(mutex_);
  retire_current(frame);
  if (published_ >= 0) sets_[size_t(published_)].state = State::free;
  published_ = -1;
}

}  // namespace pushpull::renderer
