#include "gpu_mesh.hpp"

#include "pipelines.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/vk_check.hpp"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pushpull::renderer::detail {
namespace {

template <typename T>
Buffer upload(const Context& context, std::span<const T> data, VkBufferUsageFlags usage) {
  const VkDeviceSize bytes = std::max<VkDeviceSize>(data.size_bytes(), 16);
  Buffer buffer = create_buffer(context, bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
  Buffer staging = create_buffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  std::memset(staging.mapped, 0, bytes);
  if (!data.empty()) std::memcpy(staging.mapped, data.data(), data.size_bytes());
  submit_and_wait(context, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd, staging.buffer.get(), buffer.buffer.get(), 1, &region);
  });
  return buffer;
}

void check_size(const char* what, size_t got, size_t expected) {
  if (got != expected)
    throw std::invalid_argument(std::string("RenderMesh: ") + what + " has " + std::to_string(got) +
                                " values, expected " + std::to_string(expected));
}

}  // namespace

GpuMesh GpuMesh::create(const Context& context, const RenderMesh& mesh, bool streamed, uint32_t slots,
                        uint32_t vertex_sets) {
  const size_t v = mesh.vertex_count();
  if (mesh.positions.size() % 3 != 0) throw std::invalid_argument("RenderMesh: positions is not #V*3 floats");
  if (mesh.indices.size() % 3 != 0) throw std::invalid_argument("RenderMesh: indices is not #T*3");
  for (uint32_t index : mesh.indices)
    if (index >= v) throw std::invalid_argument("RenderMesh: index " + std::to_string(index) + " >= #V");
  if (!mesh.normals.empty()) check_size("normals", mesh.normals.size(), 3 * v);
  if (!mesh.uvs.empty()) check_size("uvs", mesh.uvs.size(), 2 * v);
  if (!mesh.scalars.empty()) check_size("scalars", mesh.scalars.size(), v);
  if (!mesh.overlays.empty()) check_size("overlays", mesh.overlays.size(), v);

  GpuMesh gpu;
  gpu.vertex_count = static_cast<uint32_t>(v);
  gpu.submeshes = mesh.submeshes;
  if (gpu.submeshes.empty()) gpu.submeshes.push_back({0, static_cast<uint32_t>(mesh.indices.size()), -1});
  for (const auto& sub : gpu.submeshes)
    if (size_t{sub.first_index} + sub.index_count > mesh.indices.size())
      throw std::invalid_argument("RenderMesh: a submesh runs past the index buffer");

  const VkBufferUsageFlags vertex = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  const std::vector<float> computed_normals =
      mesh.normals.empty() ? compute_vertex_normals(mesh.positions, mesh.indices) : std::vector<float>{};
  const std::vector<float> zeros_uv =
      mesh.uvs.empty() ? std::vector<float>(2 * v, 0.0f) : std::vector<float>{};
  const std::vector<float> zeros_scalar =
      mesh.scalars.empty() ? std::vector<float>(v, 0.0f) : std::vector<float>{};
  const std::vector<OverlayWeights> zeros_overlay =
      mesh.overlays.empty() ? std::vector<OverlayWeights>(v) : std::vector<OverlayWeights>{};
  static_assert(sizeof(OverlayWeights) == 3 * sizeof(float));

  gpu.positions_ = upload<float>(context, mesh.positions, vertex);
  gpu.normals_ = upload<float>(context, mesh.normals.empty() ? computed_normals : mesh.normals, vertex);
  gpu.uvs_ = upload<float>(context, mesh.uvs.empty() ? zeros_uv : mesh.uvs, vertex);
  gpu.scalars_ = upload<float>(context, mesh.scalars.empty() ? zeros_scalar : mesh.scalars, vertex);
  gpu.overlays_ =
      upload<OverlayWeights>(context, mesh.overlays.empty() ? zeros_overlay : mesh.overlays, vertex);
  gpu.indices_ = upload<uint32_t>(context, mesh.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);

  if (streamed) {
    gpu.staging_.resize(slots);
    for (Staging& s : gpu.staging_)
      s.buffer = create_buffer(context, std::max<VkDeviceSize>(16, 10 * v * sizeof(float)),
                               VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (vertex_sets > 0 && v > 0) {
      // Bound as vertex buffers and written by the CPU: only where that memory is also device local (else the
      // GPU would read vertices over the bus every frame; the staging copies stay).
      const VkMemoryPropertyFlags props = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT |
                                          VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                          VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      try {
        std::vector<float*> bases;
        for (uint32_t i = 0; i < vertex_sets; ++i) {
          gpu.sets_.push_back(create_buffer(context, 7 * v * sizeof(float), vertex, props));
          bases.push_back(static_cast<float*>(gpu.sets_.back().mapped));
        }
        gpu.stream_ = std::make_shared<VertexStream>(uint32_t(v), std::move(bases));
      } catch (const VulkanError&) {  // no such memory type (or too little of it): the staging copies only
        gpu.sets_.clear();
      }
    }
  }
  return gpu;
}

void GpuMesh::stage(uint32_t slot, std::span<const float> positions, std::span<const float> normals,
                    std::span<const float> scalars, std::span<const OverlayWeights> overlays) {
  if (staging_.empty()) throw std::invalid_argument("update_vertices: the mesh was not created streamed");
  const size_t v = vertex_count;
  if (!positions.empty()) check_size("positions", positions.size(), 3 * v);
  if (!normals.empty()) check_size("normals", normals.size(), 3 * v);
  if (!scalars.empty()) check_size("scalars", scalars.size(), v);
  if (!overlays.empty()) check_size("overlays", overlays.size(), v);
  Staging& s = staging_[slot];
  auto* base = static_cast<float*>(s.buffer.mapped);
  if (!positions.empty()) {
    std::memcpy(base, positions.data(), positions.size_bytes());
    s.positions = true;
  }
  if (!normals.empty()) {
    std::memcpy(base + 3 * v, normals.data(), normals.size_bytes());
    s.normals = true;
  }
  if (!scalars.empty()) {
    std::memcpy(base + 6 * v, scalars.data(), scalars.size_bytes());
    s.scalars = true;
  }
  if (!overlays.empty()) {
    std::memcpy(base + 7 * v, overlays.data(), overlays.size_bytes());
    s.overlays = true;
  }
}

uint64_t GpuMesh::record_pending_uploads(VkCommandBuffer cmd, uint32_t slot) {
  if (staging_.empty()) return 0;
  Staging& s = staging_[slot];
  if (!s.positions && !s.normals && !s.scalars && !s.overlays) return 0;
  const VkDeviceSize v = vertex_count;
  struct Copy {
    bool pending;
    VkBuffer dst;
    VkDeviceSize src_offset;
    VkDeviceSize bytes;
  };
  const std::array<Copy, 4> copies{
      Copy{s.positions, positions_.buffer.get(), 0, 3 * v * sizeof(float)},
      Copy{s.normals, normals_.buffer.get(), 3 * v * sizeof(float), 3 * v * sizeof(float)},
      Copy{s.scalars, scalars_.buffer.get(), 6 * v * sizeof(float), v * sizeof(float)},
      Copy{s.overlays, overlays_.buffer.get(), 7 * v * sizeof(float), 3 * v * sizeof(float)}};
  // Earlier frames on this queue may still read these vertex buffers: copy after they are done (WAR),
  // and make the copy visible to this frame's vertex fetch.
  VkMemoryBarrier2 before{};
  before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  before.srcStageMask = VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT;
  before.dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  before.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &before;
  vkCmdPipelineBarrier2(cmd, &dep);
  uint64_t bytes = 0;
  for (const Copy& copy : copies) {
    if (!copy.pending) continue;
    VkBufferCopy region{copy.src_offset, 0, copy.bytes};
    vkCmdCopyBuffer(cmd, s.buffer.buffer.get(), copy.dst, 1, &region);
    bytes += copy.bytes;
  }
  VkMemoryBarrier2 after{};
  after.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  after.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  after.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  after.dstStageMask = VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT;
  after.dstAccessMask = VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT;
  dep.pMemoryBarriers = &after;
  vkCmdPipelineBarrier2(cmd, &dep);
  s.positions = s.normals = s.scalars = s.overlays = false;
  return bytes;
}

void GpuMesh::bind(VkCommandBuffer cmd) const {
  std::array<VkBuffer, kBindingCount> buffers{positions_.buffer.get(), normals_.buffer.get(),
                                              uvs_.buffer.get(), scalars_.buffer.get(),
                                              overlays_.buffer.get()};
  std::array<VkDeviceSize, kBindingCount> offsets{};
  if (frame_set_ >= 0) {
    const VkBuffer set = sets_[size_t(frame_set_)].buffer.get();
    const VkDeviceSize v = vertex_count;
    buffers[kPositions] = buffers[kNormals] = buffers[kScalars] = set;
    offsets[kNormals] = 3 * v * sizeof(float);
    offsets[kScalars] = 6 * v * sizeof(float);
  }
  vkCmdBindVertexBuffers(cmd, 0, kBindingCount, buffers.data(), offsets.data());
  vkCmdBindIndexBuffer(cmd, indices_.buffer.get(), 0, VK_INDEX_TYPE_UINT32);
}

}  // namespace pushpull::renderer::detail
