// pushpull::renderer::VertexStream: zero-copy streaming of a streamed mesh's positions, normals and scalars.
//
// A ring of "vertex sets" in memory that is both host visible and device local (lavapipe, integrated GPUs,
// ReBAR), bound directly as the mesh's vertex buffers: a producer (any thread) acquires a free set, writes
// into its mapped memory and publishes it; the renderer's thread binds the newest published set in each
// frame and gives a set back to the free list only once every frame that drew it has finished (the frames'
// fences). Nothing is copied on the frame's thread.
//
// Sets: RendererOptions::frames_in_flight + 3: the frames not yet known finished and the one being built may
// each draw another set (frames_in_flight), one published set waits for the next frame, and two may be held
// unpublished at once (a finished conversion not yet taken by the frame loop while the converter writes the
// next). acquire() returns an empty Lease when every set is taken anyway (more producers than that): the
// caller falls back to Renderer::update_vertices.
//
// Ownership: made and owned by the Renderer (Renderer::vertex_stream), shared with the producers; the sets'
// memory belongs to the Renderer, so every Lease must be gone before the Renderer is destroyed.
// Thread-safety: acquire, publish and Lease's members from any thread (one mutex, plain memory only; no
// Vulkan call). begin_frame and detach: the renderer's thread only (the Renderer calls them).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace pushpull::renderer {

class VertexStream : public std::enable_shared_from_this<VertexStream> {
 public:
  // A set being written: positions (#V*3), normals (#V*3) and scalars (#V) floats, all to be written (the
  // set's previous contents are undefined). Given back to the free list when destroyed unpublished.
  class Lease {
   public:
    Lease() = default;
    Lease(Lease&& other) noexcept { *this = std::move(other); }
    Lease& operator=(Lease&& other) noexcept;
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { reset(); }
    explicit operator bool() const { return stream_ != nullptr; }
    void reset();  // gives the set back unpublished

    [[nodiscard]] std::span<float> positions() const;
    [[nodiscard]] std::span<float> normals() const;
    [[nodiscard]] std::span<float> scalars() const;

   private:
    friend class VertexStream;
    std::shared_ptr<VertexStream> stream_;
    uint32_t set_ = 0;
  };

  // bases: each set's mapped memory, 7 * vertex_count floats (positions | normals | scalars).
  VertexStream(uint32_t vertex_count, std::vector<float*> bases);

  [[nodiscard]] uint32_t vertex_count() const { return vertex_count_; }
  [[nodiscard]] size_t set_count() const { return sets_.size(); }

  // Any thread: a free set to write, or an empty Lease when none is free.
  [[nodiscard]] Lease acquire();
  // Any thread: the set becomes the newest; the next frame the renderer builds draws it. A set published
  // earlier and not yet drawn goes back to the free list.
  void publish(Lease&& lease);

  // Renderer's thread. Frame `frame` is being built and every frame before `frames_finished` has finished:
  // frees the sets only those frames drew, makes the newest published set current. Returns the set frame
  // `frame` draws (-1: none, the mesh's own buffers).
  int begin_frame(uint64_t frame, uint64_t frames_finished);
  // Renderer's thread: the mesh's own buffers are drawn again from frame `frame` on (update_vertices gave new
  // positions, normals or scalars after the sets); a set published before is dropped.
  void detach(uint64_t frame);

 private:
  enum class State : uint8_t { free, writing, published, current, retiring };
  struct Set {
    float* base = nullptr;
    State state = State::free;
    uint64_t last_frame = 0;  // retiring: the last frame that drew it
  };
  void give_back(uint32_t set);
  void retire_current(uint64_t frame);

  uint32_t vertex_count_ = 0;
  mutable std::mutex mutex_;
  std::vector<Set> sets_;
  int published_ = -1;
  int current_ = -1;
};

}  // namespace pushpull::renderer
