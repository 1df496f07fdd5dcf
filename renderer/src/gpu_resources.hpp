// Internal: buffers, images and one-shot command submission on a Context. Not a public header.
// One dedicated VkDeviceMemory per resource: the renderer holds tens of resources, not thousands.
#pragma once

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/unique_handle.hpp"

#include <cstdint>
#include <functional>

namespace pushpull::renderer::detail {

struct Buffer {
  UniqueBuffer buffer;
  UniqueMemory memory;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // persistently mapped when host visible, else null
};

// host_visible: HOST_VISIBLE|HOST_COHERENT and mapped; otherwise DEVICE_LOCAL.
Buffer create_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible);
// With these memory properties; mapped when they include HOST_VISIBLE. Throws VulkanError when no memory
// type has them.
Buffer create_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                     VkMemoryPropertyFlags properties);

struct Image {
  UniqueImage image;
  UniqueMemory memory;
  UniqueImageView view;  // all layers (2D array view when layers > 1)
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  uint32_t layers = 1;
  uint32_t mip_levels = 1;
};

struct ImageDesc {
  VkExtent2D extent{};
  VkFormat format = VK_FORMAT_R8G8B8A8_SRGB;
  VkImageUsageFlags usage = 0;
  uint32_t layers = 1;
  uint32_t mip_levels = 1;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};
Image create_image(const Context& context, const ImageDesc& desc);

// A single-layer view of one layer of an image.
UniqueImageView create_layer_view(const Context& context, VkImage image, VkFormat format, uint32_t layer,
                                  VkImageAspectFlags aspect);

// Records commands into a fresh command buffer, submits them and waits for completion.
// For setup work (texture uploads, readbacks), never inside the frame loop.
// A command pool on the context's queue family. Throws (PP_VK_CHECK) on failure.
UniqueCommandPool create_command_pool(const Context& context, VkCommandPoolCreateFlags flags);

void submit_and_wait(const Context& context, const std::function<void(VkCommandBuffer)>& record);

// Layout transition of `layers` layers starting at base_layer, mip 0..levels-1, with explicit stages.
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access, uint32_t base_layer = 0,
                   uint32_t layers = 1, uint32_t base_mip = 0, uint32_t levels = 1);

}  // namespace pushpull::renderer::detail
