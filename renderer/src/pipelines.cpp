#include "pipelines.hpp"

#include "pushpull/renderer/vk_check.hpp"

// SPIR-V generated at build time by glslangValidator (renderer/CMakeLists.txt).
#include "mesh.frag.h"
#include "mesh.vert.h"
#include "overlay2d.frag.h"
#include "overlay2d.vert.h"

#include <array>
#include <span>

namespace pushpull::renderer::detail {
namespace {

UniqueDescriptorSetLayout create_set_layout(VkDevice device,
                                            std::span<const VkDescriptorSetLayoutBinding> bindings) {
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout));
  return UniqueDescriptorSetLayout(device, layout);
}

UniqueShaderModule create_module(VkDevice device, std::span<const uint32_t> code) {
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
  return UniqueShaderModule(device, module);
}

struct PipelineDesc {
  std::span<const uint32_t> vertex_code;
  std::span<const uint32_t> fragment_code;
  std::span<const VkVertexInputBindingDescription> bindings;
  std::span<const VkVertexInputAttributeDescription> attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  bool depth = true;
  bool blend = false;
  bool depth_attachment = true;  // false: the pass has no depth attachment (drawing over a copied image)
};

UniquePipeline create_pipeline(const Context& context, VkPipelineLayout layout, VkFormat colour_format,
                               VkSampleCountFlagBits samples, const PipelineDesc& desc) {
  VkDevice device = context.device();
  UniqueShaderModule vertex = create_module(device, desc.vertex_code);
  UniqueShaderModule fragment = create_module(device, desc.fragment_code);
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {};
  stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex.get();
  stages[0].pName = "main";
  stages[1] = {};
  stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment.get();
  stages[1].pName = "main";

  VkPipelineVertexInputStateCreateInfo vertex_input{};

  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(desc.bindings.size());
  vertex_input.pVertexBindingDescriptions = desc.bindings.data();
  vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(desc.attributes.size());
  vertex_input.pVertexAttributeDescriptions = desc.attributes.data();

  VkPipelineInputAssemblyStateCreateInfo assembly{};

  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = desc.topology;

  VkPipelineViewportStateCreateInfo viewport{};

  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;

  VkPipelineRasterizationStateCreateInfo raster{};

  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;  // open CAD surfaces are seen from both sides
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;

  VkPipelineMultisampleStateCreateInfo multisample{};

  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = samples;

  VkPipelineDepthStencilStateCreateInfo depth{};

  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = desc.depth ? VK_TRUE : VK_FALSE;
  depth.depthWriteEnable = desc.depth ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;

  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                    VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.blend) {
    blend_attachment.blendEnable = VK_TRUE;
    blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
    blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;

  const std::array<VkDynamicState, 2> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{};
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = static_cast<uint32_t>(dynamic_states.size());
  dynamic.pDynamicStates = dynamic_states.data();

  VkPipelineRenderingCreateInfo rendering{};

  rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &colour_format;
  rendering.depthAttachmentFormat = desc.depth_attachment ? kDepthFormat : VK_FORMAT_UNDEFINED;

  VkGraphicsPipelineCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return UniquePipeline(device, pipeline);
}

}  // namespace

PipelineLayouts create_pipeline_layouts(const Context& context) {
  VkDevice device = context.device();
  PipelineLayouts layouts;
  const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  const std::array<VkDescriptorSetLayoutBinding, 1> frame_bindings{
      VkDescriptorSetLayoutBinding{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, both, nullptr}};
  layouts.frame = create_set_layout(device, frame_bindings);
  const std::array<VkDescriptorSetLayoutBinding, 6> material_bindings{
      VkDescriptorSetLayoutBinding{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                                   nullptr},
      VkDescriptorSetLayoutBinding{1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      VkDescriptorSetLayoutBinding{2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      VkDescriptorSetLayoutBinding{3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      VkDescriptorSetLayoutBinding{4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      VkDescriptorSetLayoutBinding{5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                   VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
  layouts.material = create_set_layout(device, material_bindings);
  const std::array<VkDescriptorSetLayoutBinding, 1> overlay_bindings{VkDescriptorSetLayoutBinding{
      0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
  layouts.overlay = create_set_layout(device, overlay_bindings);

  {
    const std::array<VkDescriptorSetLayout, 2> sets{layouts.frame.get(), layouts.material.get()};
    VkPushConstantRange push{both, 0, sizeof(DrawPushGpu)};
    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = static_cast<uint32_t>(sets.size());
    info.pSetLayouts = sets.data();
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    PP_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    layouts.mesh = UniquePipelineLayout(device, layout);
  }
  {
    VkDescriptorSetLayout set = layouts.overlay.get();
    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::vec4)};
    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = 1;
    info.pSetLayouts = &set;
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    PP_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    layouts.overlay2d = UniquePipelineLayout(device, layout);
  }
  return layouts;
}

UniquePipeline create_mesh_pipeline(const Context& context, VkPipelineLayout layout, VkFormat colour_format,
                                    VkSampleCountFlagBits samples, bool depth_test, bool depth_attachment) {
  const std::array<VkVertexInputBindingDescription, kBindingCount> bindings{
      VkVertexInputBindingDescription{kPositions, 3 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{kNormals, 3 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{kUvs, 2 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{kScalars, sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX},
      VkVertexInputBindingDescription{kOverlays, 3 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX}};
  const std::array<VkVertexInputAttributeDescription, kBindingCount> attributes{
      VkVertexInputAttributeDescription{0, kPositions, VK_FORMAT_R32G32B32_SFLOAT, 0},
      VkVertexInputAttributeDescription{1, kNormals, VK_FORMAT_R32G32B32_SFLOAT, 0},
      VkVertexInputAttributeDescription{2, kUvs, VK_FORMAT_R32G32_SFLOAT, 0},
      VkVertexInputAttributeDescription{3, kScalars, VK_FORMAT_R32_SFLOAT, 0},
      VkVertexInputAttributeDescription{4, kOverlays, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  PipelineDesc desc;
  desc.vertex_code = mesh_vert_spv;
  desc.fragment_code = mesh_frag_spv;
  desc.bindings = bindings;
  desc.attributes = attributes;
  desc.depth = depth_test && depth_attachment;
  desc.depth_attachment = depth_attachment;
  return create_pipeline(context, layout, colour_format, samples, desc);
}

UniquePipeline create_overlay_pipeline(const Context& context, VkPipelineLayout layout,
                                       VkFormat colour_format, VkSampleCountFlagBits samples,
                                       bool depth_attachment) {
  PipelineDesc desc;
  desc.depth_attachment = depth_attachment;
  desc.vertex_code = overlay2d_vert_spv;
  desc.fragment_code = overlay2d_frag_spv;
  desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
  desc.depth = false;
  desc.blend = true;
  return create_pipeline(context, layout, colour_format, samples, desc);
}

}  // namespace pushpull::renderer::detail
