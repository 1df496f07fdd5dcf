// Internal: a mesh on the GPU (one device-local buffer per vertex stream + indices) and, for
// streamed meshes, a ring of host-visible staging slots (one per frame in flight) and, where the device has
// memory both device local and host visible, a VertexStream of vertex sets bound directly (zero copy).
#pragma once

#include "gpu_resources.hpp"
#include "pushpull/renderer/types.hpp"
#include "pushpull/renderer/vertex_stream.hpp"

#include <memory>

#include <span>
#include <vector>

namespace pushpull::renderer::detail {

class GpuMesh {
 public:
  // vertex_sets: the VertexStream's sets (0: none); made only when such memory exists.
  static GpuMesh create(const Context& context, const RenderMesh& mesh, bool streamed, uint32_t slots,
                        uint32_t vertex_sets = 0);

  // Copies new data into staging slot `slot` (the caller has waited for that slot's fence).
  void stage(uint32_t slot, std::span<const float> positions, std::span<const float> normals,
             std::span<const float> scalars, std::span<const OverlayWeights> overlays = {});
  // Records the copies staged in `slot` with their barriers; returns the bytes copied.
  uint64_t record_pending_uploads(VkCommandBuffer cmd, uint32_t slot);
  // Binds the mesh's buffers, positions, normals and scalars from the vertex set of the frame being built
  // (begin_frame) when there is one.
  void bind(VkCommandBuffer cmd) const;
  // Frame `frame` is being built, frames before `frames_finished` have finished: picks its vertex set.
  void begin_frame(uint64_t frame, uint64_t frames_finished) {
    frame_set_ = stream_ ? stream_->begin_frame(frame, frames_finished) : -1;
  }
  [[nodiscard]] const std::shared_ptr<VertexStream>& stream() const { return stream_; }

  std::vector<RenderMesh::Submesh> submeshes;
  uint32_t vertex_count = 0;

 private:
  struct Staging {
    Buffer buffer;  // positions (#V*3) | normals (#V*3) | scalars (#V) | overlays (#V*3) floats
    bool positions = false;
    bool normals = false;
    bool scalars = false;
    bool overlays = false;
  };
  Buffer positions_;
  Buffer normals_;
  Buffer uvs_;
  Buffer scalars_;
  Buffer overlays_;
  Buffer indices_;
  std::vector<Staging> staging_;
  std::vector<Buffer> sets_;  // the stream's sets: positions (#V*3) | normals (#V*3) | scalars (#V) floats
  std::shared_ptr<VertexStream> stream_;
  int frame_set_ = -1;  // the set the frame being built draws
};

}  // namespace pushpull::renderer::detail
