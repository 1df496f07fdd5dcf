#include "pushpull/renderer/offscreen_target.hpp"

#include "gpu_resources.hpp"
#include "pushpull/renderer/vk_check.hpp"

#include <cstring>
#include <stdexcept>

namespace pushpull::renderer {

using namespace detail;

struct OffscreenTarget::Impl {
  const Context* context = nullptr;
  Image image;
  std::vector<UniqueImageView> layer_views;
};

OffscreenTarget::OffscreenTarget(const Context& context, uint32_t width, uint32_t height, uint32_t layers,
                                 VkFormat format)
    : impl_(std::make_unique<Impl>()) {
  if (width == 0 || height == 0 || layers == 0) throw std::invalid_argument("OffscreenTarget: zero size");
  impl_->context = &context;
  ImageDesc desc;
  desc.extent = {width, height};
  desc.format = format;
  desc.layers = layers;
  desc.usage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  impl_->image = create_image(context, desc);
  for (uint32_t layer = 0; layer < layers; ++layer)
    impl_->layer_views.push_back(
        create_layer_view(context, impl_->image.image.get(), format, layer, VK_IMAGE_ASPECT_COLOR_BIT));
}

OffscreenTarget::~OffscreenTarget() = default;
OffscreenTarget::OffscreenTarget(OffscreenTarget&&) noexcept = default;
OffscreenTarget& OffscreenTarget::operator=(OffscreenTarget&&) noexcept = default;

ColorTarget OffscreenTarget::layer_target(uint32_t layer) const {
  if (layer >= impl_->layer_views.size()) throw std::out_of_range("OffscreenTarget: no such layer");
  ColorTarget target;
  target.image = impl_->image.image.get();
  target.view = impl_->layer_views[layer].get();
  target.layer = layer;
  target.initial_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  target.final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  return target;
}

RenderTargets OffscreenTarget::targets() const {
  RenderTargets targets;
  targets.extent = impl_->image.extent;
  targets.format = impl_->image.format;
  for (uint32_t layer = 0; layer < impl_->layer_views.size(); ++layer)
    targets.views.push_back(layer_target(layer));
  return targets;
}

TextureRGBA8 OffscreenTarget::read_back(uint32_t layer) const {
  const Context& context = *impl_->context;
  if (layer >= impl_->layer_views.size()) throw std::out_of_range("OffscreenTarget: no such layer");
  const VkFormat format = impl_->image.format;
  if (format != VK_FORMAT_R8G8B8A8_SRGB && format != VK_FORMAT_R8G8B8A8_UNORM &&
      format != VK_FORMAT_B8G8R8A8_SRGB && format != VK_FORMAT_B8G8R8A8_UNORM)
    throw std::invalid_argument("OffscreenTarget::read_back: only 8-bit RGBA/BGRA formats");
  const VkExtent2D extent = impl_->image.extent;
  const VkDeviceSize bytes = VkDeviceSize{extent.width} * extent.height * 4;
  Buffer buffer = create_buffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  PP_VK_CHECK(vkQueueWaitIdle(context.queue()));
  submit_and_wait(context, [&](VkCommandBuffer cmd) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, layer, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, impl_->image.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           buffer.buffer.get(), 1, &region);
  });
  TextureRGBA8 result;
  result.width = extent.width;
  result.height = extent.height;
  result.pixels.resize(bytes);
  std::memcpy(result.pixels.data(), buffer.mapped, bytes);
  if (format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM)
    for (size_t i = 0; i < result.pixels.size(); i += 4) std::swap(result.pixels[i], result.pixels[i + 2]);
  return result;
}

VkExtent2D OffscreenTarget::extent() const {
  return impl_->image.extent;
}
VkFormat OffscreenTarget::format() const {
  return impl_->image.format;
}

}  // namespace pushpull::renderer
