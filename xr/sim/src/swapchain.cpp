// Swapchains: images on the application's VkDevice, handed out in COLOR_ATTACHMENT_OPTIMAL (colour)
// or DEPTH_STENCIL_ATTACHMENT_OPTIMAL (depth), with the acquire -> wait -> release order checked.
#include "dispatch.hpp"
#include "vulkan_util.hpp"

#include <algorithm>

namespace pushpull::xrsim {
namespace {

// In the order the runtime prefers them (the spec asks for preference order).
constexpr VkFormat kCandidateFormats[] = {
    VK_FORMAT_R8G8B8A8_SRGB,      VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM,
    VK_FORMAT_B8G8R8A8_UNORM,     VK_FORMAT_D32_SFLOAT,    VK_FORMAT_D24_UNORM_S8_UINT,
    VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D16_UNORM,
};

bool is_depth(VkFormat f) {
  return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT ||
         f == VK_FORMAT_D16_UNORM;
}
bool has_stencil(VkFormat f) {
  return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

std::vector<VkFormat> supported_formats(VkPhysicalDevice device) {
  std::vector<VkFormat> out;
  for (VkFormat f : kCandidateFormats) {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(device, f, &p);
    const VkFormatFeatureFlags need =
        is_depth(f) ? VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT
                    : (VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT);
    if ((p.optimalTilingFeatures & need) == need) out.push_back(f);
  }
  return out;
}

XrResult XRAPI_CALL enumerate_formats(XrSession handle, uint32_t capacity, uint32_t* count,
                                      int64_t* formats) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (capacity != 0 && formats == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  std::vector<VkFormat> f = supported_formats(s->vk.physical_device);
  if (s->instance->config.unorm_first)  // UNORM before sRGB, BGRA before RGBA: the app must pick by its needs
    std::stable_sort(f.begin(), f.end(), [](VkFormat a, VkFormat b) {
      auto rank = [](VkFormat x) {
        switch (x) {
          case VK_FORMAT_B8G8R8A8_UNORM:
            return 0;
          case VK_FORMAT_R8G8B8A8_UNORM:
            return 1;
          case VK_FORMAT_B8G8R8A8_SRGB:
            return 2;
          case VK_FORMAT_R8G8B8A8_SRGB:
            return 3;
          default:
            return 4;
        }
      };
      return rank(a) < rank(b);
    });
  return two_call(capacity, count, static_cast<uint32_t>(f.size()), [&](uint32_t i) { formats[i] = f[i]; });
}

VkImageUsageFlags vulkan_usage(XrSwapchainUsageFlags u, VkFormat f) {
  // Colour images can always be copied from (capture) and rendered to; depth images are attachments.
  VkImageUsageFlags v = is_depth(f) ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                    : (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  if (u & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) v |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (u & XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT) v |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (u & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) v |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (u & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) v |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (u & XR_SWAPCHAIN_USAGE_INPUT_ATTACHMENT_BIT_MND) v |= VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
  return v;
}

// Moves image `index` from UNDEFINED to the layout images are handed out in. Done at its first acquire
// because xrAcquireSwapchainImage is one of the calls during which the runtime may use the queue.
VkResult lay_out(const Swapchain& sc, uint32_t index) {
  const bool depth = is_depth(sc.format);
  return submit_and_wait(sc.session->vk, [&](VkCommandBuffer cb) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout =
        depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.dstAccessMask =
        depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = sc.images[index];
    const VkImageAspectFlags aspect =
        depth ? (VK_IMAGE_ASPECT_DEPTH_BIT | (has_stencil(sc.format) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0))
              : VK_IMAGE_ASPECT_COLOR_BIT;
    b.subresourceRange = {aspect, 0, sc.info.mipCount, 0, sc.info.arraySize * sc.info.faceCount};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &b);
  });
}

XrResult XRAPI_CALL create_swapchain(XrSession handle, const XrSwapchainCreateInfo* info, XrSwapchain* out) {
  Lock lock(big_lock());
  Session* s = nullptr;
  if (const XrResult r = get_session(handle, &s); XR_FAILED(r)) return r;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_SWAPCHAIN_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) return XR_ERROR_FEATURE_UNSUPPORTED;
  if (info->createFlags & ~XrSwapchainCreateFlags(XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT |
                                                  XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT))
    return XR_ERROR_VALIDATION_FAILURE;
  const std::vector<VkFormat> formats = supported_formats(s->vk.physical_device);
  const auto format = static_cast<VkFormat>(info->format);
  if (std::find(formats.begin(), formats.end(), format) == formats.end())
    return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
  if (info->width == 0 || info->height == 0 || info->width > 4096 || info->height > 4096 ||
      info->arraySize == 0 || info->mipCount == 0 || (info->faceCount != 1 && info->faceCount != 6) ||
      info->sampleCount != 1)
    return XR_ERROR_VALIDATION_FAILURE;
  if (is_depth(format) && (info->usageFlags & XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT))
    return XR_ERROR_FEATURE_UNSUPPORTED;
  if (!is_depth(format) && (info->usageFlags & XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT))
    return XR_ERROR_FEATURE_UNSUPPORTED;
  if (s->instance->config.refuse_transfer_source && (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT))
    return XR_ERROR_FEATURE_UNSUPPORTED;
  if (s->instance->config.refuse_transfer_source_as_format &&
      (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT))
    return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;

  if (info->faceCount == 6 && info->width != info->height) return XR_ERROR_VALIDATION_FAILURE;
  {
    // The usage the application asks for must be possible with this format on this device.
    VkImageFormatProperties props;
    const VkImageCreateFlags flags =
        ((info->usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT
                                                                    : 0) |
        (info->faceCount == 6 ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0);
    if (vkGetPhysicalDeviceImageFormatProperties(
            s->vk.physical_device, format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
            vulkan_usage(info->usageFlags, format), flags, &props) != VK_SUCCESS ||
        info->arraySize * info->faceCount > props.maxArrayLayers || info->mipCount > props.maxMipLevels)
      return XR_ERROR_FEATURE_UNSUPPORTED;
  }
  auto sc = std::make_unique<Swapchain>();
  sc->session = s;
  sc->info = *info;
  sc->info.next = nullptr;
  sc->format = format;
  const uint32_t count = (info->createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) ? 1 : 3;
  const VkDevice device = s->vk.device;
  const uint32_t layers = info->arraySize * info->faceCount;
  XrResult result = XR_SUCCESS;
  for (uint32_t i = 0; i < count && XR_SUCCEEDED(result); ++i) {
    VkImageCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ci.flags =
        (info->usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT : 0;
    if (info->faceCount == 6) ci.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {info->width, info->height, 1};
    ci.mipLevels = info->mipCount;
    ci.arrayLayers = layers;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = vulkan_usage(info->usageFlags, format);
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    if (vkCreateImage(device, &ci, nullptr, &image) != VK_SUCCESS) {
      result = XR_ERROR_RUNTIME_FAILURE;
      break;
    }
    sc->images.push_back(image);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        find_memory_type(s->vk.physical_device, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (ai.memoryTypeIndex == UINT32_MAX)
      ai.memoryTypeIndex = find_memory_type(s->vk.physical_device, req.memoryTypeBits, 0);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (vkAllocateMemory(device, &ai, nullptr, &memory) != VK_SUCCESS) {
      result = XR_ERROR_RUNTIME_FAILURE;
      break;
    }
    sc->memory.push_back(memory);
    if (vkBindImageMemory(device, image, memory, 0) != VK_SUCCESS) result = XR_ERROR_RUNTIME_FAILURE;
  }
  sc->laid_out.assign(sc->images.size(), false);
  Swapchain* raw = sc.release();
  register_handle(raw, HandleKind::swapchain);
  s->swapchains.push_back(raw);
  if (XR_FAILED(result)) {
    destroy_swapchain(raw);
    return result;
  }
  *out = to_handle<XrSwapchain>(raw);
  return XR_SUCCESS;
}

XrResult get_swapchain(XrSwapchain handle, Swapchain** out) {
  Swapchain* sc = lookup<Swapchain>(handle);
  if (sc == nullptr) return XR_ERROR_HANDLE_INVALID;
  *out = sc;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL destroy_swapchain_entry(XrSwapchain handle) {
  Lock lock(big_lock());
  Swapchain* sc = nullptr;
  if (const XrResult r = get_swapchain(handle, &sc); XR_FAILED(r)) return r;
  destroy_swapchain(sc);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_images(XrSwapchain handle, uint32_t capacity, uint32_t* count,
                                     XrSwapchainImageBaseHeader* images) {
  Lock lock(big_lock());
  Swapchain* sc = nullptr;
  if (const XrResult r = get_swapchain(handle, &sc); XR_FAILED(r)) return r;
  if (capacity != 0 && images == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  auto* vk_images = reinterpret_cast<XrSwapchainImageVulkanKHR*>(images);
  for (uint32_t i = 0; i < capacity; ++i)
    if (vk_images[i].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR) return XR_ERROR_VALIDATION_FAILURE;
  return two_call(capacity, count, static_cast<uint32_t>(sc->images.size()),
                  [&](uint32_t i) { vk_images[i].image = sc->images[i]; });
}

XrResult XRAPI_CALL acquire_image(XrSwapchain handle, const XrSwapchainImageAcquireInfo* info,
                                  uint32_t* index) {
  Lock lock(big_lock());
  Swapchain* sc = nullptr;
  if (const XrResult r = get_swapchain(handle, &sc); XR_FAILED(r)) return r;
  if ((info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) || index == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  if (sc->acquired.size() == sc->images.size()) return XR_ERROR_CALL_ORDER_INVALID;
  if ((sc->info.createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) && sc->static_used)
    return XR_ERROR_CALL_ORDER_INVALID;
  if (!sc->laid_out[sc->next_index]) {
    if (lay_out(*sc, sc->next_index) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
    sc->laid_out[sc->next_index] = true;
  }
  sc->static_used = true;
  *index = sc->next_index;
  sc->acquired.push_back(sc->next_index);
  sc->next_index = (sc->next_index + 1) % static_cast<uint32_t>(sc->images.size());
  return sc->session->loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

XrResult XRAPI_CALL wait_image(XrSwapchain handle, const XrSwapchainImageWaitInfo* info) {
  Lock lock(big_lock());
  Swapchain* sc = nullptr;
  if (const XrResult r = get_swapchain(handle, &sc); XR_FAILED(r)) return r;
  if (info == nullptr || info->type != XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (sc->acquired.empty() || sc->waited) return XR_ERROR_CALL_ORDER_INVALID;
  if (sc->session->instance->config.wait_timeout && !sc->wait_timed_out) {
    sc->wait_timed_out =
        true;  // quirk: the first wait for each acquired image times out (the spec allows it)
    return XR_TIMEOUT_EXPIRED;
  }
  sc->wait_timed_out = false;
  sc->waited = true;  // the compositor never holds an image: it is ready at once
  return sc->session->loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

XrResult XRAPI_CALL release_image(XrSwapchain handle, const XrSwapchainImageReleaseInfo* info) {
  Lock lock(big_lock());
  Swapchain* sc = nullptr;
  if (const XrResult r = get_swapchain(handle, &sc); XR_FAILED(r)) return r;
  if (info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (sc->acquired.empty() || !sc->waited) return XR_ERROR_CALL_ORDER_INVALID;
  sc->last_released = sc->acquired.front();
  sc->acquired.pop_front();
  sc->waited = false;
  return sc->session->loss_pending ? XR_SESSION_LOSS_PENDING : XR_SUCCESS;
}

}  // namespace

void destroy_swapchain(Swapchain* sc) {
  const VkDevice device = sc->session->vk.device;
  for (VkImage image : sc->images) vkDestroyImage(device, image, nullptr);
  for (VkDeviceMemory memory : sc->memory) vkFreeMemory(device, memory, nullptr);
  auto& list = sc->session->swapchains;
  list.erase(std::remove(list.begin(), list.end(), sc), list.end());
  unregister_handle(sc);
  delete sc;
}

void add_swapchain_functions(FunctionTable& t) {
  PUSHPULL_XR_ADD(t, xrEnumerateSwapchainFormats, enumerate_formats);
  PUSHPULL_XR_ADD(t, xrCreateSwapchain, create_swapchain);
  PUSHPULL_XR_ADD(t, xrDestroySwapchain, destroy_swapchain_entry);
  PUSHPULL_XR_ADD(t, xrEnumerateSwapchainImages, enumerate_images);
  PUSHPULL_XR_ADD(t, xrAcquireSwapchainImage, acquire_image);
  PUSHPULL_XR_ADD(t, xrWaitSwapchainImage, wait_image);
  PUSHPULL_XR_ADD(t, xrReleaseSwapchainImage, release_image);
}

}  // namespace pushpull::xrsim
