// Internal: a mesh on the GPU (one device-local buffer per vertex stream + indices) and, for
// streamed meshes, a ring of host-visible staging slots (one per frame in flight).
#pragma once

#include "gpu_resources.hpp"
#include "pushpull/renderer/types.hpp"

#include <span>
#include <vector>

namespace pushpull::renderer::detail {

class GpuMesh {
 public:
  static GpuMesh create(const Context& context, const RenderMesh& mesh, bool streamed, uint32_t slots);

  // Copies new data into staging slot `slot` (the caller has waited for that slot's fence).
  void stage(uint32_t slot, std::span<const float> positions, std::span<const float> normals,
             std::span<const float> scalars, std::span<const OverlayWeights> overlays = {});
  // Records the copies staged in `slot` with their barriers; returns the bytes copied.
  uint64_t record_pending_uploads(VkCommandBuffer cmd, uint32_t slot);
  void bind(VkCommandBuffer cmd) const;

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
};

}  // namespace pushpull::renderer::detail
