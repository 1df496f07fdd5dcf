#include "pushpull/xr/swapchain.hpp"

#include <chrono>
#include <string>
#include <thread>

namespace pushpull::xr {

struct Swapchain::Impl {
  XrInstance instance = XR_NULL_HANDLE;
  XrSwapchain swapchain = XR_NULL_HANDLE;
  std::vector<VkImage> images;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
  bool transfer_source = false;
  bool acquired = false;

  ~Impl() {
    const RuntimeCallScope runtime;
    if (swapchain != XR_NULL_HANDLE) xrDestroySwapchain(swapchain);
  }
};

Swapchain::Swapchain(XrInstance instance, XrSession session, int64_t format, uint32_t width, uint32_t height,
                     bool transfer_source)
    : impl_(std::make_unique<Impl>()) {
  impl_->instance = instance;
  impl_->format = VkFormat(format);
  impl_->width = width;
  impl_->height = height;
  XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO};
  info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
  if (transfer_source) info.usageFlags |= XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT;
  info.format = format;
  info.sampleCount = 1;
  info.width = width;
  info.height = height;
  info.faceCount = 1;
  info.arraySize = 1;
  info.mipCount = 1;
  // Into a local handle: a failed call leaves its output undefined, and ~Impl destroys what it holds.
  XrSwapchain swapchain = XR_NULL_HANDLE;
  const RuntimeCallScope runtime;  // swapchain images are made on our device
  XrResult created = xrCreateSwapchain(session, &info, &swapchain);
  // Refused usage: XR_ERROR_FEATURE_UNSUPPORTED per the spec, but runtimes differ
  // (XR_ERROR_VALIDATION_FAILURE, XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED for the pair,
  // XR_ERROR_RUNTIME_FAILURE): any failure with the extra usage is tried again without it, and only the plain
  // swapchain's failure is reported.
  if (XR_FAILED(created) && created != XR_ERROR_SESSION_LOST && created != XR_ERROR_INSTANCE_LOST &&
      transfer_source) {
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;  // the mirror draws its own view instead
    transfer_source = false;
    swapchain = XR_NULL_HANDLE;
    created = xrCreateSwapchain(session, &info, &swapchain);
  }
  check_xr(created, instance, "xrCreateSwapchain(session, &info, &swapchain)", __FILE__, __LINE__);
  impl_->swapchain = swapchain;
  impl_->transfer_source = transfer_source;
  uint32_t count = 0;
  PUSHPULL_XR_CHECK(instance, xrEnumerateSwapchainImages(impl_->swapchain, 0, &count, nullptr));
  std::vector<XrSwapchainImageVulkan2KHR> images(count, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
  PUSHPULL_XR_CHECK(instance,
                    xrEnumerateSwapchainImages(impl_->swapchain, count, &count,
                                               reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())));
  for (const auto& image : images) impl_->images.push_back(image.image);
}

Swapchain::~Swapchain() = default;
Swapchain::Swapchain(Swapchain&&) noexcept = default;
Swapchain& Swapchain::operator=(Swapchain&&) noexcept = default;

uint32_t Swapchain::acquire() {
  uint32_t index = 0;
  XrSwapchainImageAcquireInfo acquire_info{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
  PUSHPULL_XR_CHECK(impl_->instance, xrAcquireSwapchainImage(impl_->swapchain, &acquire_info, &index));
  // XR_TIMEOUT_EXPIRED is a success code, but the image is not ready: it may not be drawn into or released
  // until a wait says XR_SUCCESS. Runtimes may time out even an infinite wait: waited again for up to 2 s.
  XrSwapchainImageWaitInfo wait_info{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wait_info.timeout = XR_INFINITE_DURATION;
  constexpr std::chrono::seconds kWaitLimit{2};
  const auto first = std::chrono::steady_clock::now();
  while (PUSHPULL_XR_CHECK(impl_->instance, xrWaitSwapchainImage(impl_->swapchain, &wait_info)) ==
         XR_TIMEOUT_EXPIRED) {
    if (std::chrono::steady_clock::now() - first > kWaitLimit) {
      throw XrError(
          std::string(__FILE__) + ":" + std::to_string(__LINE__) +
              ": xrWaitSwapchainImage(impl_->swapchain, &wait_info) kept returning XR_TIMEOUT_EXPIRED "
              "for 2 s of an infinite wait: the runtime never hands over the swapchain image",
          XR_TIMEOUT_EXPIRED);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  impl_->acquired = true;  // release() needs a waited image (an unwaited one: XR_ERROR_CALL_ORDER_INVALID)
  return index;
}

void Swapchain::release() {
  if (!impl_->acquired) return;
  impl_->acquired = false;
  XrSwapchainImageReleaseInfo release_info{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
  PUSHPULL_XR_CHECK(impl_->instance, xrReleaseSwapchainImage(impl_->swapchain, &release_info));
}

XrSwapchain Swapchain::handle() const { return impl_->swapchain; }
const std::vector<VkImage>& Swapchain::images() const { return impl_->images; }
VkFormat Swapchain::format() const { return impl_->format; }
uint32_t Swapchain::width() const { return impl_->width; }
uint32_t Swapchain::height() const { return impl_->height; }
bool Swapchain::transfer_source() const {
  return impl_->transfer_source;
}

}  // namespace pushpull::xr
