#include "gpu_resources.hpp"

#include "pushpull/renderer/vk_check.hpp"

namespace pushpull::renderer::detail {

namespace {

UniqueMemory allocate_memory(const Context& context, const VkMemoryRequirements& requirements,
                             VkMemoryPropertyFlags properties) {
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = context.find_memory_type(requirements.memoryTypeBits, properties);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  PP_VK_CHECK(vkAllocateMemory(context.device(), &alloc, nullptr, &memory));
  return UniqueMemory(context.device(), memory);
}

}  // namespace

UniqueCommandPool create_command_pool(const Context& context, VkCommandPoolCreateFlags flags) {
  VkCommandPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  info.flags = flags;
  info.queueFamilyIndex = context.queue_family_index();
  VkCommandPool pool = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateCommandPool(context.device(), &info, nullptr, &pool));
  return UniqueCommandPool(context.device(), pool);
}

Buffer create_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible) {
  const VkMemoryPropertyFlags props =
      host_visible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                   : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  return create_buffer(context, size, usage, props);
}

Buffer create_buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                     VkMemoryPropertyFlags props) {
  VkDevice device = context.device();
  Buffer result;
  result.size = size;
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
  result.buffer = UniqueBuffer(device, buffer);

  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  result.memory = allocate_memory(context, requirements, props);
  PP_VK_CHECK(vkBindBufferMemory(device, buffer, result.memory.get(), 0));
  if (props & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
    PP_VK_CHECK(vkMapMemory(device, result.memory.get(), 0, VK_WHOLE_SIZE, 0, &result.mapped));
  return result;
}

Image create_image(const Context& context, const ImageDesc& desc) {
  VkDevice device = context.device();
  Image result;
  result.format = desc.format;
  result.extent = desc.extent;
  result.layers = desc.layers;
  result.mip_levels = desc.mip_levels;

  VkImageCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.extent.width, desc.extent.height, 1};
  info.mipLevels = desc.mip_levels;
  info.arrayLayers = desc.layers;
  info.samples = desc.samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateImage(device, &info, nullptr, &image));
  result.image = UniqueImage(device, image);

  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device, image, &requirements);
  result.memory = allocate_memory(context, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  PP_VK_CHECK(vkBindImageMemory(device, image, result.memory.get(), 0));

  VkImageViewCreateInfo view_info{};

  view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view_info.image = image;
  view_info.viewType = desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = desc.format;
  view_info.subresourceRange = {desc.aspect, 0, desc.mip_levels, 0, desc.layers};
  VkImageView view = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateImageView(device, &view_info, nullptr, &view));
  result.view = UniqueImageView(device, view);
  return result;
}

UniqueImageView create_layer_view(const Context& context, VkImage image, VkFormat format, uint32_t layer,
                                  VkImageAspectFlags aspect) {
  VkImageViewCreateInfo view_info{};
  view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view_info.image = image;
  view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view_info.format = format;
  view_info.subresourceRange = {aspect, 0, 1, layer, 1};
  VkImageView view = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateImageView(context.device(), &view_info, nullptr, &view));
  return UniqueImageView(context.device(), view);
}

void submit_and_wait(const Context& context, const std::function<void(VkCommandBuffer)>& record) {
  VkDevice device = context.device();
  UniqueCommandPool pool = create_command_pool(context, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT);

  VkCommandBufferAllocateInfo alloc{};

  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = pool.get();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  PP_VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  PP_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  PP_VK_CHECK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fence_info{};

  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence_handle = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateFence(device, &fence_info, nullptr, &fence_handle));
  UniqueFence fence(device, fence_handle);
  VkCommandBufferSubmitInfo cmd_info{};
  cmd_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  cmd_info.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  PP_VK_CHECK(vkQueueSubmit2(context.queue(), 1, &submit, fence.get()));
  PP_VK_CHECK(vkWaitForFences(device, 1, &fence_handle, VK_TRUE, UINT64_MAX));
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access, uint32_t base_layer,
                   uint32_t layers, uint32_t base_mip, uint32_t levels) {
  VkImageMemoryBarrier2 barrier{};
  barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  barrier.srcStageMask = src_stage;
  barrier.srcAccessMask = src_access;
  barrier.dstStageMask = dst_stage;
  barrier.dstAccessMask = dst_access;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, base_mip, levels, base_layer, layers};
  VkDependencyInfo dependency{};
  dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

}  // namespace pushpull::renderer::detail
