#include "pushpull/renderer/mirror_window.hpp"

#include "pushpull/renderer/unique_handle.hpp"
#include "pushpull/renderer/vk_check.hpp"
#include "x11_error_guard.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <deque>
#include <string>
#include <utility>

namespace pushpull::renderer {

namespace {

// GLFW's description of its last error (": ..."), or "" when it gave none.
std::string glfw_error_text() {
  const char* description = nullptr;
  if (glfwGetError(&description) == GLFW_NO_ERROR || description == nullptr) return "";
  return std::string(": ") + description;
}

void init_glfw() {
  if (glfwInit() != GLFW_TRUE)
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED,
                      "glfwInit failed" + glfw_error_text() + " (no display? set DISPLAY or use xvfb-run)");
  if (glfwVulkanSupported() != GLFW_TRUE)
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "GLFW finds no Vulkan loader" + glfw_error_text());
}

}  // namespace

struct MirrorWindow::Impl {
  const Context& context;
  GLFWwindow* window = nullptr;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  std::vector<VkImage> images;
  std::vector<UniqueImageView> views;
  std::vector<UniqueSemaphore> acquired;  // rotating, images.size() + 1 of them
  std::vector<UniqueSemaphore> rendered;  // one per swapchain image
  uint32_t next_acquire = 0;
  bool needs_recreate = false;
  bool lost = false;         // the surface or the window is gone (closed from outside)
  bool blit_target = false;  // the swapchain images take transfers (TRANSFER_DST usage)
  std::vector<int> key_presses;
  double scroll = 0.0;  // since the last poll_events()
  // The pointer at each button press and release since the frame last read it, oldest first: a click or a
  // short drag begun and ended between two polls (a slow frame) still shows the loop its press, its last
  // position with the button held, and its release, one a poll. Bounded: past kMaxQueued transitions (a
  // stalled loop) the oldest go.
  static constexpr std::size_t kMaxQueued = 32;
  std::deque<Pointer> queued;
  Pointer polled;  // what pointer() returns until the next poll_events()
  // The cursor as the last motion (or enter) event placed it. glfwGetCursorPos asks the X server where the
  // pointer is now, which for a press followed by a move within one poll is already past the press.
  double event_x = 0.0, event_y = 0.0;

  Pointer live() const {
    Pointer p;
    glfwGetCursorPos(window, &p.x, &p.y);
    glfwGetWindowSize(window, &p.window_width, &p.window_height);
    p.left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    p.right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    p.middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    p.shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
              glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    return p;
  }
  // Each button's state as the callbacks left it: GLFW releases the buttons held when the window loses the
  // focus, and the physical release that follows comes as a second release, which must not look like a
  // press (a held snapshot) followed by a release.
  std::array<bool, GLFW_MOUSE_BUTTON_LAST + 1> down{};

  // GLFW has set the button's new state when it calls back; the cursor is where the last motion event put it.
  void button_changed(int button, int action) {
    if (button < 0 || button > GLFW_MOUSE_BUTTON_LAST) return;
    const bool pressed = action == GLFW_PRESS;
    if (down[std::size_t(button)] == pressed) return;  // a release of a button already up
    down[std::size_t(button)] = pressed;
    Pointer now = live();
    now.x = event_x, now.y = event_y;
    if (!pressed) {  // first the position the button was released at, still held
      Pointer held = now;
      if (button == GLFW_MOUSE_BUTTON_LEFT) held.left = true;
      if (button == GLFW_MOUSE_BUTTON_RIGHT) held.right = true;
      if (button == GLFW_MOUSE_BUTTON_MIDDLE) held.middle = true;
      queued.push_back(held);
    }
    queued.push_back(now);
    while (queued.size() > kMaxQueued) queued.pop_front();
  }

  explicit Impl(const Context& c) : context(c) {}

  UniqueSemaphore make_semaphore() {
    VkSemaphoreCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    VkSemaphore semaphore = VK_NULL_HANDLE;
    PP_VK_CHECK(vkCreateSemaphore(context.device(), &info, nullptr, &semaphore));
    return UniqueSemaphore(context.device(), semaphore);
  }

  void destroy_swapchain() {
    views.clear();
    acquired.clear();
    rendered.clear();
    images.clear();
    if (swapchain != VK_NULL_HANDLE) vkDestroySwapchainKHR(context.device(), swapchain, nullptr);
    swapchain = VK_NULL_HANDLE;
  }

  void create_swapchain() {
    VkPhysicalDevice gpu = context.physical_device();
    VkBool32 supported = VK_FALSE;
    PP_VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(gpu, context.queue_family_index(), surface, &supported));
    if (!supported)
      throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "the graphics queue cannot present to the window");
    VkSurfaceCapabilitiesKHR caps;
    PP_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu, surface, &caps));
    uint32_t count = 0;
    PP_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    PP_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(gpu, surface, &count, formats.data()));
    VkSurfaceFormatKHR chosen = formats.at(0);
    for (const auto& f : formats)
      if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
          f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
        chosen = f;
    format = chosen.format;
    if (caps.currentExtent.width != UINT32_MAX) {
      extent = caps.currentExtent;
    } else {
      int w = 0, h = 0;
      glfwGetFramebufferSize(window, &w, &h);
      extent = {std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
    }
    if (extent.width == 0 || extent.height == 0) return;  // minimised
    uint32_t image_count = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    info.surface = surface;
    info.minImageCount = image_count;
    info.imageFormat = chosen.format;
    info.imageColorSpace = chosen.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    blit_target = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;
    if (blit_target) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    // The mirror must never hold back the loop that feeds a 90 Hz headset to a 60 Hz desktop display: mailbox
    // (newest image wins), else immediate, else FIFO (always available; it blocks when the display is slower).
    uint32_t mode_count = 0;
    PP_VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(context.physical_device(), surface, &mode_count, nullptr));
    std::vector<VkPresentModeKHR> modes(mode_count);
    PP_VK_CHECK(
        vkGetPhysicalDeviceSurfacePresentModesKHR(context.physical_device(), surface, &mode_count, modes.data()));
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR})
      if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) info.presentMode = wanted;
    info.clipped = VK_TRUE;
    PP_VK_CHECK(vkCreateSwapchainKHR(context.device(), &info, nullptr, &swapchain));
    PP_VK_CHECK(vkGetSwapchainImagesKHR(context.device(), swapchain, &count, nullptr));
    images.resize(count);
    PP_VK_CHECK(vkGetSwapchainImagesKHR(context.device(), swapchain, &count, images.data()));
    for (VkImage image : images) {
      VkImageViewCreateInfo view_info{};
      view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
      view_info.image = image;
      view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
      view_info.format = format;
      view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      VkImageView view = VK_NULL_HANDLE;
      PP_VK_CHECK(vkCreateImageView(context.device(), &view_info, nullptr, &view));
      views.emplace_back(context.device(), view);
      rendered.push_back(make_semaphore());
    }
    for (size_t i = 0; i <= images.size(); ++i) acquired.push_back(make_semaphore());
    next_acquire = 0;
  }

  void recreate() {
    PP_VK_CHECK(vkDeviceWaitIdle(context.device()));
    destroy_swapchain();
    create_swapchain();
    needs_recreate = false;
  }
};

std::vector<std::string> MirrorWindow::required_instance_extensions() {
  init_glfw();
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (names == nullptr)
    throw VulkanError(VK_ERROR_EXTENSION_NOT_PRESENT, "GLFW cannot create Vulkan surfaces here");
  return std::vector<std::string>(names, names + count);
}

MirrorWindow::MirrorWindow(const Context& context, uint32_t width, uint32_t height, const std::string& title)
    : impl_(std::make_unique<Impl>(context)) {
  init_glfw();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  impl_->window = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (impl_->window == nullptr)
    throw VulkanError(VK_ERROR_INITIALIZATION_FAILED, "glfwCreateWindow failed" + glfw_error_text());
  detail::watch_x11_window(impl_->window);
  detail::install_x11_error_guard();
  glfwSetWindowUserPointer(impl_->window, impl_.get());
  glfwSetKeyCallback(impl_->window, [](GLFWwindow* window, int key, int, int action, int) {
    if (action == GLFW_PRESS)
      static_cast<Impl*>(glfwGetWindowUserPointer(window))->key_presses.push_back(key);
  });
  glfwGetCursorPos(impl_->window, &impl_->event_x, &impl_->event_y);
  glfwSetCursorPosCallback(impl_->window, [](GLFWwindow* window, double x, double y) {
    Impl& w = *static_cast<Impl*>(glfwGetWindowUserPointer(window));
    w.event_x = x, w.event_y = y;
  });
  glfwSetMouseButtonCallback(impl_->window, [](GLFWwindow* window, int button, int action, int) {
    static_cast<Impl*>(glfwGetWindowUserPointer(window))->button_changed(button, action);
  });
  glfwSetScrollCallback(impl_->window, [](GLFWwindow* window, double, double dy) {
    static_cast<Impl*>(glfwGetWindowUserPointer(window))->scroll += dy;
  });
  PP_VK_CHECK(glfwCreateWindowSurface(context.instance(), impl_->window, nullptr, &impl_->surface));
  impl_->create_swapchain();
}

MirrorWindow::~MirrorWindow() {
  detail::set_x11_connection_lost({});
  vkDeviceWaitIdle(impl_->context.device());
  impl_->destroy_swapchain();
  if (impl_->surface != VK_NULL_HANDLE)
    vkDestroySurfaceKHR(impl_->context.instance(), impl_->surface, nullptr);
  if (impl_->window != nullptr) glfwDestroyWindow(impl_->window);
}

MirrorWindow::LastWords MirrorWindow::on_connection_lost(std::function<void()> last_words) {
  detail::set_x11_connection_lost(std::move(last_words));
  return LastWords{};
}

MirrorWindow::LastWords::~LastWords() {
  if (set_) detail::set_x11_connection_lost({});
}

std::optional<MirrorWindow::Frame> MirrorWindow::acquire(uint64_t timeout_ns) {
  Impl& w = *impl_;
  if (lost()) return std::nullopt;
  if (w.needs_recreate || w.swapchain == VK_NULL_HANDLE) {
    try {
      w.recreate();
    } catch (const VulkanError& e) {
      if (e.result() != VK_ERROR_SURFACE_LOST_KHR) throw;
      w.lost = true;
    }
    if (w.lost || w.swapchain == VK_NULL_HANDLE) return std::nullopt;
  }
  VkSemaphore acquired = w.acquired[w.next_acquire].get();
  uint32_t index = 0;
  // Bounded: a window system that stalls (or a WSI that blocks on a window destroyed from outside) costs
  // the loop a mirror frame, never its frames for good.
  const VkResult result =
      vkAcquireNextImageKHR(w.context.device(), w.swapchain, timeout_ns, acquired, VK_NULL_HANDLE, &index);
  if (result == VK_TIMEOUT || result == VK_NOT_READY) return std::nullopt;  // nothing acquired or signalled
  if (result == VK_ERROR_SURFACE_LOST_KHR) {  // nothing was acquired: the window is gone
    w.lost = true;
    return std::nullopt;
  }
  if (result == VK_ERROR_OUT_OF_DATE_KHR) {
    w.needs_recreate = true;
    return std::nullopt;
  }
  if (result != VK_SUCCESS && result != VK_SUBOPTIMAL_KHR) PP_VK_CHECK(result);
  if (result == VK_SUBOPTIMAL_KHR) w.needs_recreate = true;
  w.next_acquire = uint32_t((w.next_acquire + 1) % w.acquired.size());
  Frame frame;
  frame.image_index = index;
  frame.targets.extent = w.extent;
  frame.targets.format = w.format;
  ColorTarget target;
  target.image = w.images[index];
  target.view = w.views[index].get();
  target.initial_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  target.final_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  frame.targets.views.push_back(target);
  frame.sync.wait = acquired;
  frame.sync.signal = w.rendered[index].get();
  return frame;
}

void MirrorWindow::present(const Frame& frame) {
  Impl& w = *impl_;
  VkPresentInfoKHR info{};
  info.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &frame.sync.signal;
  info.swapchainCount = 1;
  info.pSwapchains = &w.swapchain;
  info.pImageIndices = &frame.image_index;
  const VkResult result = vkQueuePresentKHR(w.context.queue(), &info);
  if (result == VK_ERROR_SURFACE_LOST_KHR) {  // the window is gone; the image is released with the swapchain
    w.lost = true;
    return;
  }
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
    w.needs_recreate = true;
    return;
  }
  PP_VK_CHECK(result);
}

void MirrorWindow::abandon(const Frame& /*frame*/) {
  impl_->needs_recreate = true;
}

bool MirrorWindow::should_close() const {
  return lost() || glfwWindowShouldClose(impl_->window) == GLFW_TRUE;
}
bool MirrorWindow::lost() const {
  return impl_->lost || detail::x11_window_gone();
}
void MirrorWindow::poll_events() {
  Impl& w = *impl_;
  glfwPollEvents();
  detail::install_x11_error_guard();  // again: GLFW resets it after its own guarded requests
  if (lost()) return;                 // the window's state would be garbage
  if (w.queued.empty()) {
    w.polled = w.live();
  } else {
    w.polled = w.queued.front();
    w.queued.pop_front();
    glfwGetWindowSize(w.window, &w.polled.window_width, &w.polled.window_height);
  }
  w.polled.left_release_queued = w.polled.left && std::any_of(w.queued.begin(), w.queued.end(),
                                                              [](const Pointer& p) { return !p.left; });
  w.polled.scroll = std::exchange(w.scroll, 0.0);
}
std::vector<int> MirrorWindow::take_key_presses() {
  return std::exchange(impl_->key_presses, {});
}
MirrorWindow::Pointer MirrorWindow::pointer() const {
  return impl_->polled;
}
void MirrorWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(impl_->window, title.c_str());
}
VkExtent2D MirrorWindow::extent() const {
  return impl_->extent;
}

bool MirrorWindow::accepts_blit() const {
  return impl_->blit_target;
}

}  // namespace pushpull::renderer
