#include "textures.hpp"

#include "pushpull/renderer/vk_check.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace pushpull::renderer::detail {

StagedTexture stage_texture(const Context& context, const TextureRGBA8& texture) {
  if (texture.width == 0 || texture.height == 0 ||
      texture.pixels.size() != size_t{texture.width} * texture.height * 4)
    throw std::invalid_argument("texture: pixel buffer does not hold width * height * 4 bytes");
  ImageDesc desc;
  desc.extent = {texture.width, texture.height};
  desc.format = texture.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.mip_levels = static_cast<uint32_t>(std::bit_width(std::max(texture.width, texture.height)));
  StagedTexture staged{create_image(context, desc),
                       create_buffer(context, texture.pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true)};
  std::memcpy(staged.staging.mapped, texture.pixels.data(), texture.pixels.size());
  return staged;
}

void record_texture_upload(VkCommandBuffer cmd, const Image& image, const Buffer& staging) {
  const VkImage handle = image.image.get();
  const uint32_t levels = image.mip_levels;
  image_barrier(cmd, handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, 0, 1, 0, levels);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {image.extent.width, image.extent.height, 1};
  vkCmdCopyBufferToImage(cmd, staging.buffer.get(), handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);

  int32_t w = static_cast<int32_t>(image.extent.width);
  int32_t h = static_cast<int32_t>(image.extent.height);
  for (uint32_t level = 1; level < levels; ++level) {
    image_barrier(cmd, handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT, 0, 1, level - 1, 1);
    const int32_t nw = std::max(1, w / 2);
    const int32_t nh = std::max(1, h / 2);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
    blit.srcOffsets[1] = {w, h, 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
    blit.dstOffsets[1] = {nw, nh, 1};
    vkCmdBlitImage(cmd, handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, handle,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    w = nw;
    h = nh;
  }
  // Levels 0..levels-2 are TRANSFER_SRC, the last is TRANSFER_DST.
  if (levels > 1)
    image_barrier(cmd, handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 0, 1, 0, levels - 1);
  image_barrier(cmd, handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 0, 1, levels - 1, 1);
}

Image upload_texture(const Context& context, const TextureRGBA8& texture) {
  StagedTexture staged = stage_texture(context, texture);
  submit_and_wait(context,
                  [&](VkCommandBuffer cmd) { record_texture_upload(cmd, staged.image, staged.staging); });
  return std::move(staged.image);
}

UniqueSampler create_sampler(const Context& context, VkSamplerAddressMode address_mode) {
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = address_mode;
  info.addressModeV = address_mode;
  info.addressModeW = address_mode;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  return UniqueSampler(context.device(), sampler);
}

}  // namespace pushpull::renderer::detail
