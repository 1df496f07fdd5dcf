#include "compositor.hpp"

#include "sim_math.hpp"
#include "vulkan_util.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace pushpull::xrsim {
namespace {

XrResult check_sub_image(const Session& s, const XrSwapchainSubImage& sub) {
  const Swapchain* sc = lookup<Swapchain>(sub.swapchain);
  if (sc == nullptr || sc->session != &s) return XR_ERROR_HANDLE_INVALID;
  if (sc->last_released < 0) return XR_ERROR_LAYER_INVALID;
  const XrRect2Di& r = sub.imageRect;
  if (r.offset.x < 0 || r.offset.y < 0 || r.extent.width <= 0 || r.extent.height <= 0 ||
      static_cast<int64_t>(r.offset.x) + r.extent.width > static_cast<int64_t>(sc->info.width) ||
      static_cast<int64_t>(r.offset.y) + r.extent.height > static_cast<int64_t>(sc->info.height))
    return XR_ERROR_SWAPCHAIN_RECT_INVALID;
  if (sub.imageArrayIndex >= sc->info.arraySize) return XR_ERROR_VALIDATION_FAILURE;
  return XR_SUCCESS;
}

XrResult check_space(const Session& s, XrSpace handle) {
  const Space* space = lookup<Space>(handle);
  return (space == nullptr || space->session != &s) ? XR_ERROR_HANDLE_INVALID : XR_SUCCESS;
}

// Writes the view's image to `file`; false with `why` set when it could not.
bool capture_view(const Session& s, const XrSwapchainSubImage& sub, const std::string& file,
                  std::string& why) {
  const Swapchain* sc = lookup<Swapchain>(sub.swapchain);
  const VkFormat f = sc->format;
  const bool bgra = f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM;
  const bool rgba = f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_R8G8B8A8_UNORM;
  if (!bgra && !rgba) {
    why = "8-bit RGBA/BGRA swapchains only";
    return false;
  }
  why = "the copy from the swapchain image failed";
  const VulkanBinding& vk = s.vk;
  const uint32_t w = static_cast<uint32_t>(sub.imageRect.extent.width);
  const uint32_t h = static_cast<uint32_t>(sub.imageRect.extent.height);
  const VkDeviceSize size = VkDeviceSize(w) * h * 4;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = size;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (vkCreateBuffer(vk.device, &bi, nullptr, &buffer) != VK_SUCCESS) return false;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(vk.device, buffer, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex =
      find_memory_type(vk.physical_device, req.memoryTypeBits,
                       VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  bool ok = ai.memoryTypeIndex != UINT32_MAX &&
            vkAllocateMemory(vk.device, &ai, nullptr, &memory) == VK_SUCCESS &&
            vkBindBufferMemory(vk.device, buffer, memory, 0) == VK_SUCCESS;
  const VkImage image = sc->images[static_cast<std::size_t>(sc->last_released)];
  if (ok) {
    const VkResult r = submit_and_wait(vk, [&](VkCommandBuffer cb) {
      VkImageMemoryBarrier b{};
      b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
      b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
      b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      b.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      b.image = image;
      b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, sub.imageArrayIndex, 1};
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                           nullptr, 0, nullptr, 1, &b);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, sub.imageArrayIndex, 1};
      copy.imageOffset = {sub.imageRect.offset.x, sub.imageRect.offset.y, 0};
      copy.imageExtent = {w, h, 1};
      vkCmdCopyImageToBuffer(cb, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
      std::swap(b.oldLayout, b.newLayout);
      b.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
      b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                           nullptr, 0, nullptr, 1, &b);
    });
    ok = r == VK_SUCCESS;
  }
  if (ok) {
    void* mapped = nullptr;
    ok = vkMapMemory(vk.device, memory, 0, size, 0, &mapped) == VK_SUCCESS;
    if (ok) {
      std::vector<unsigned char> pixels(static_cast<std::size_t>(size));
      std::memcpy(pixels.data(), mapped, pixels.size());
      vkUnmapMemory(vk.device, memory);
      for (std::size_t i = 0; i < pixels.size(); i += 4) {
        if (bgra) std::swap(pixels[i], pixels[i + 2]);
        pixels[i + 3] = 255;  // what the headset shows is opaque
      }
      // Whole or not at all: written beside it, then renamed into place (a process killed mid-write leaves no
      // half picture under the capture's name).
      // Encoded in memory, then written with every write, flush and close checked (stb's own file writer
      // ignores them: a full disk renamed a truncated picture into place).
      std::vector<unsigned char> png;
      const auto append = [](void* context, void* data, int size) {
        auto& out = *static_cast<std::vector<unsigned char>*>(context);
        const auto* bytes = static_cast<const unsigned char*>(data);
        out.insert(out.end(), bytes, bytes + size);
      };
      const std::string part = file + ".part";
      ok = stbi_write_png_to_func(append, &png, static_cast<int>(w), static_cast<int>(h), 4, pixels.data(),
                                  static_cast<int>(w * 4)) != 0;
      if (!ok) why = "the PNG encoder failed";
      if (ok) {
        errno = 0;
        std::FILE* out = std::fopen(part.c_str(), "wb");
        ok = out != nullptr && std::fwrite(png.data(), 1, png.size(), out) == png.size() &&
             std::fflush(out) == 0;
        if (out != nullptr && std::fclose(out) != 0) ok = false;
        ok = ok && std::rename(part.c_str(), file.c_str()) == 0;
        if (!ok) {
          why = std::string("cannot write it: ") + (errno != 0 ? std::strerror(errno) : "unknown error");
          std::remove(part.c_str());
        }
      }
    }
  }
  if (memory != VK_NULL_HANDLE) vkFreeMemory(vk.device, memory, nullptr);
  vkDestroyBuffer(vk.device, buffer, nullptr);
  return ok;
}

}  // namespace

XrResult validate_layers(const Session& s, const XrFrameEndInfo& info) {
  if (info.layerCount > XR_MIN_COMPOSITION_LAYERS_SUPPORTED) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
  if (info.layerCount > 0 && info.layers == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < info.layerCount; ++i) {
    const XrCompositionLayerBaseHeader* layer = info.layers[i];
    if (layer == nullptr) return XR_ERROR_LAYER_INVALID;
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
      const auto* p = reinterpret_cast<const XrCompositionLayerProjection*>(layer);
      if (const XrResult r = check_space(s, p->space); XR_FAILED(r)) return r;
      if (p->viewCount != 2 || p->views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
      for (uint32_t v = 0; v < p->viewCount; ++v) {
        const XrCompositionLayerProjectionView& view = p->views[v];
        if (view.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
        if (!quat_is_unit(view.pose.orientation)) return XR_ERROR_POSE_INVALID;
        if (const XrResult r = check_sub_image(s, view.subImage); XR_FAILED(r)) return r;
      }
    } else if (layer->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {
      const auto* q = reinterpret_cast<const XrCompositionLayerQuad*>(layer);
      if (const XrResult r = check_space(s, q->space); XR_FAILED(r)) return r;
      if (!quat_is_unit(q->pose.orientation)) return XR_ERROR_POSE_INVALID;
      if (const XrResult r = check_sub_image(s, q->subImage); XR_FAILED(r)) return r;
    } else {
      return XR_ERROR_LAYER_INVALID;
    }
  }
  return XR_SUCCESS;
}

int capture_frame(Session& s, const XrFrameEndInfo& info, int64_t frame_index) {
  const Config& c = s.instance->config;
  const bool every = c.capture_every > 0 && frame_index % c.capture_every == 0;
  if (c.capture_dir.empty() || !(s.capture_requested || every)) return 0;
  if (info.layerCount == 0) return 0;  // nothing shown this frame: keep the request for the next one
  s.capture_requested = false;
  std::error_code ec;
  std::filesystem::create_directories(c.capture_dir, ec);
  int written = 0;
  const auto write = [&](const XrSwapchainSubImage& sub, const std::string& what) {
    char name[96];
    std::snprintf(name, sizeof name, "frame_%06lld_%s.png", static_cast<long long>(frame_index),
                  what.c_str());
    const std::string file = (std::filesystem::path(c.capture_dir) / name).string();
    if (std::string why; capture_view(s, sub, file, why))
      ++written;
    else
      std::fprintf(stderr, "pushpull xr sim: could not capture %s (%s)\n", file.c_str(), why.c_str());
  };
  bool projection_written = false;
  int quads = 0;
  for (uint32_t i = 0; i < info.layerCount; ++i) {
    const XrCompositionLayerBaseHeader* layer = info.layers[i];
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION && !projection_written) {
      // What each eye sees: the first projection layer (the runtime does not blend layers).
      const auto* p = reinterpret_cast<const XrCompositionLayerProjection*>(layer);
      for (uint32_t v = 0; v < p->viewCount; ++v) write(p->views[v].subImage, v == 0 ? "left" : "right");
      projection_written = true;
    } else if (layer->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {
      write(reinterpret_cast<const XrCompositionLayerQuad*>(layer)->subImage,
            "quad" + std::to_string(quads++));
    }
  }
  return written;
}

}  // namespace pushpull::xrsim
