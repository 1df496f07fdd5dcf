// Internal: descriptor-set layouts and graphics pipelines (dynamic rendering, Vulkan 1.3).
#pragma once

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/unique_handle.hpp"

#include <glm/glm.hpp>

namespace pushpull::renderer::detail {

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Vertex streams of a mesh: one binding each, so a streamed attribute can be replaced alone.
enum VertexBinding : uint32_t {
  kPositions = 0,
  kNormals = 1,
  kUvs = 2,
  kScalars = 3,
  kOverlays = 4,
  kBindingCount = 5
};

struct ViewDataGpu {
  glm::mat4 view_projection;
  glm::vec4 eye_world;
};
// Matches FrameData in shaders/frame_data.glsl (std140).
struct FrameDataGpu {
  ViewDataGpu views[2];
  glm::vec4 up_world;
  glm::vec4 key_light_dir;
  glm::vec4 colour_params;
  glm::uvec4 mode;
};
// Matches DrawData (push constants).
struct DrawPushGpu {
  glm::mat4 T_world_mesh;
  uint32_t view_index;
  uint32_t flags;  // bit 0: colour mapped
};
// Matches MaterialData in mesh.frag (std140).
struct MaterialGpu {
  glm::vec4 base_colour;
  glm::vec4 emissive;
  glm::vec4 factors;
  glm::vec4 factors2;
};

struct PipelineLayouts {
  UniqueDescriptorSetLayout frame;     // set 0 of the mesh pipeline: FrameData
  UniqueDescriptorSetLayout material;  // set 1: MaterialData + 5 textures
  UniqueDescriptorSetLayout overlay;   // set 0 of the overlay pipeline: one texture
  UniquePipelineLayout mesh;
  UniquePipelineLayout overlay2d;
};
PipelineLayouts create_pipeline_layouts(const Context& context);

// depth_test false: drawn over everything (overlay geometry). depth_attachment false: for passes without a
// depth attachment (drawing over an image copied into the target); no depth test then.
UniquePipeline create_mesh_pipeline(const Context& context, VkPipelineLayout layout, VkFormat colour_format,
                                    VkSampleCountFlagBits samples, bool depth_test = true,
                                    bool depth_attachment = true);
UniquePipeline create_overlay_pipeline(const Context& context, VkPipelineLayout layout,
                                       VkFormat colour_format, VkSampleCountFlagBits samples,
                                       bool depth_attachment = true);

}  // namespace pushpull::renderer::detail
