// Swapchains on the application's device, acquire/wait/release order, layers at xrEndFrame and the
// compositor's PNG capture, through the loader.
#include "sim_fixture.hpp"

#include <gtest/gtest.h>

#include <stb/stb_image.h>

#include <algorithm>
#include <filesystem>

using namespace sim_test;

namespace {

class SwapchainTest : public ::testing::Test {
 protected:
  void SetUp() override { use_simulated_runtime(); }
};

std::vector<int64_t> formats(Sim& sim) {
  uint32_t n = 0;
  EXPECT_EQ(xrEnumerateSwapchainFormats(sim.session, 0, &n, nullptr), XR_SUCCESS);
  std::vector<int64_t> f(n);
  EXPECT_EQ(xrEnumerateSwapchainFormats(sim.session, n, &n, f.data()), XR_SUCCESS);
  return f;
}

XrSwapchain make_swapchain(Sim& sim, int64_t format, uint32_t array_size, XrResult expected = XR_SUCCESS,
                           XrSwapchainUsageFlags usage = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT |
                                                         XR_SWAPCHAIN_USAGE_SAMPLED_BIT) {
  XrSwapchainCreateInfo ci{XR_TYPE_SWAPCHAIN_CREATE_INFO};
  ci.usageFlags = usage;
  ci.format = format;
  ci.sampleCount = 1;
  ci.width = 64;
  ci.height = 48;
  ci.faceCount = 1;
  ci.arraySize = array_size;
  ci.mipCount = 1;
  XrSwapchain sc = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateSwapchain(sim.session, &ci, &sc), expected);
  return sc;
}

std::vector<VkImage> images(XrSwapchain sc) {
  uint32_t n = 0;
  EXPECT_EQ(xrEnumerateSwapchainImages(sc, 0, &n, nullptr), XR_SUCCESS);
  std::vector<XrSwapchainImageVulkan2KHR> imgs(n, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
  EXPECT_EQ(xrEnumerateSwapchainImages(sc, n, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(imgs.data())),
            XR_SUCCESS);
  std::vector<VkImage> out;
  for (const auto& i : imgs) out.push_back(i.image);
  return out;
}

TEST_F(SwapchainTest, OffersSrgbUnormAndDepthFormats) {
  Sim sim;
  sim.create_session();
  const auto f = formats(sim);
  for (VkFormat want : {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM,
                        VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_D32_SFLOAT})
    EXPECT_NE(std::find(f.begin(), f.end(), want), f.end()) << want;
  make_swapchain(sim, VK_FORMAT_R5G6B5_UNORM_PACK16, 1, XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
  XrSwapchain depth = make_swapchain(sim, VK_FORMAT_D32_SFLOAT, 1, XR_SUCCESS,
                                     XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
  EXPECT_EQ(images(depth).size(), 3u);
  XrSwapchain array = make_swapchain(sim, VK_FORMAT_R8G8B8A8_SRGB, 2);
  EXPECT_EQ(images(array).size(), 3u);
  // A cube swapchain (six faces) needs square faces.
  XrSwapchainCreateInfo ci{XR_TYPE_SWAPCHAIN_CREATE_INFO};
  ci.usageFlags = XR_SWAPCHAIN_USAGE_SAMPLED_BIT;
  ci.format = VK_FORMAT_R8G8B8A8_UNORM;
  ci.sampleCount = 1;
  ci.width = 32;
  ci.height = 16;
  ci.faceCount = 6;
  ci.arraySize = 1;
  ci.mipCount = 1;
  XrSwapchain cube = XR_NULL_HANDLE;
  EXPECT_EQ(xrCreateSwapchain(sim.session, &ci, &cube), XR_ERROR_VALIDATION_FAILURE);
  ci.height = 32;
  EXPECT_EQ(xrCreateSwapchain(sim.session, &ci, &cube), XR_SUCCESS);
  uint32_t index = 0;
  EXPECT_EQ(xrAcquireSwapchainImage(cube, nullptr, &index), XR_SUCCESS);
}

TEST_F(SwapchainTest, AcquireWaitReleaseOrderIsChecked) {
  Sim sim;
  sim.create_session();
  XrSwapchain sc = make_swapchain(sim, VK_FORMAT_R8G8B8A8_SRGB, 1);
  XrSwapchainImageWaitInfo wi{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wi.timeout = XR_INFINITE_DURATION;
  EXPECT_EQ(xrWaitSwapchainImage(sc, &wi), XR_ERROR_CALL_ORDER_INVALID);
  EXPECT_EQ(xrReleaseSwapchainImage(sc, nullptr), XR_ERROR_CALL_ORDER_INVALID);
  uint32_t index = 99;
  ASSERT_EQ(xrAcquireSwapchainImage(sc, nullptr, &index), XR_SUCCESS);
  EXPECT_EQ(index, 0u);
  EXPECT_EQ(xrReleaseSwapchainImage(sc, nullptr), XR_ERROR_CALL_ORDER_INVALID);  // not waited
  ASSERT_EQ(xrWaitSwapchainImage(sc, &wi), XR_SUCCESS);
  EXPECT_EQ(xrWaitSwapchainImage(sc, &wi), XR_ERROR_CALL_ORDER_INVALID);
  ASSERT_EQ(xrReleaseSwapchainImage(sc, nullptr), XR_SUCCESS);
  uint32_t a = 0, b = 0, c = 0;
  ASSERT_EQ(xrAcquireSwapchainImage(sc, nullptr, &a), XR_SUCCESS);
  ASSERT_EQ(xrAcquireSwapchainImage(sc, nullptr, &b), XR_SUCCESS);
  ASSERT_EQ(xrAcquireSwapchainImage(sc, nullptr, &c), XR_SUCCESS);
  EXPECT_EQ(a, 1u);
  EXPECT_EQ(b, 2u);
  EXPECT_EQ(c, 0u);
  EXPECT_EQ(xrAcquireSwapchainImage(sc, nullptr, &index), XR_ERROR_CALL_ORDER_INVALID);  // all acquired
  EXPECT_EQ(xrDestroySwapchain(sc), XR_SUCCESS);
  EXPECT_EQ(xrAcquireSwapchainImage(sc, nullptr, &index), XR_ERROR_HANDLE_INVALID);
}

// Clears each eye's image to a colour, submits a projection layer and checks the captured PNGs.
TEST_F(SwapchainTest, CapturesWhatEachEyeShows) {
  const std::string dir = temp_dir("capture");
  setenv("PUSHPULL_XR_SIM_CAPTURE", dir.c_str(), 1);
  setenv("PUSHPULL_XR_SIM_CAPTURE_EVERY", "1", 1);
  Sim sim;
  sim.create_session();
  sim.begin_session();
  XrSwapchain sc = make_swapchain(sim, VK_FORMAT_B8G8R8A8_UNORM, 2);
  const auto imgs = images(sc);
  XrSpace local = sim.reference_space(XR_REFERENCE_SPACE_TYPE_LOCAL);

  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(sim.vk_device, sim.queue_family, 0, &queue);
  VkCommandPoolCreateInfo pci{};
  pci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pci.queueFamilyIndex = sim.queue_family;
  VkCommandPool pool = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateCommandPool(sim.vk_device, &pci, nullptr, &pool), VK_SUCCESS);

  XrFrameState fs{XR_TYPE_FRAME_STATE};
  ASSERT_EQ(xrWaitFrame(sim.session, nullptr, &fs), XR_SUCCESS);
  ASSERT_EQ(xrBeginFrame(sim.session, nullptr), XR_SUCCESS);
  uint32_t index = 0;
  ASSERT_EQ(xrAcquireSwapchainImage(sc, nullptr, &index), XR_SUCCESS);
  XrSwapchainImageWaitInfo wi{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wi.timeout = XR_INFINITE_DURATION;
  ASSERT_EQ(xrWaitSwapchainImage(sc, &wi), XR_SUCCESS);
  {
    // Layer 0 red, layer 1 blue; the image is in COLOR_ATTACHMENT_OPTIMAL as handed out.
    VkCommandBufferAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    ai.commandPool = pool;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(sim.vk_device, &ai, &cb), VK_SUCCESS);
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    vkBeginCommandBuffer(cb, &bi);
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = imgs[index];
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 2};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr,
                         0, nullptr, 1, &b);
    const VkClearColorValue red{{1.f, 0.f, 0.f, 1.f}}, blue{{0.f, 0.f, 1.f, 1.f}};
    VkImageSubresourceRange r0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        r1{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 1, 1};
    vkCmdClearColorImage(cb, imgs[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &red, 1, &r0);
    vkCmdClearColorImage(cb, imgs[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &blue, 1, &r1);
    std::swap(b.oldLayout, b.newLayout);
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &b);
    vkEndCommandBuffer(cb);
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    ASSERT_EQ(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
    vkQueueWaitIdle(queue);
  }
  ASSERT_EQ(xrReleaseSwapchainImage(sc, nullptr), XR_SUCCESS);

  XrViewLocateInfo li{XR_TYPE_VIEW_LOCATE_INFO};
  li.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  li.displayTime = fs.predictedDisplayTime;
  li.space = local;
  XrViewState vs{XR_TYPE_VIEW_STATE};
  std::vector<XrView> views(2, {XR_TYPE_VIEW});
  uint32_t n = 0;
  ASSERT_EQ(xrLocateViews(sim.session, &li, &vs, 2, &n, views.data()), XR_SUCCESS);
  XrCompositionLayerProjectionView pv[2];
  for (uint32_t i = 0; i < 2; ++i) {
    pv[i] = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW};
    pv[i].pose = views[i].pose;
    pv[i].fov = views[i].fov;
    pv[i].subImage.swapchain = sc;
    pv[i].subImage.imageRect = {{0, 0}, {64, 48}};
    pv[i].subImage.imageArrayIndex = i;
  }
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  layer.space = local;
  layer.viewCount = 2;
  layer.views = pv;
  XrCompositionLayerQuad quad{XR_TYPE_COMPOSITION_LAYER_QUAD};
  quad.space = local;
  quad.eyeVisibility = XR_EYE_VISIBILITY_BOTH;
  quad.subImage = pv[1].subImage;
  quad.subImage.imageRect = {{0, 0}, {16, 8}};
  quad.pose = {{0, 0, 0, 1}, {0, 0, -1}};
  quad.size = {0.5f, 0.25f};
  const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<XrCompositionLayerBaseHeader*>(&layer),
                                                  reinterpret_cast<XrCompositionLayerBaseHeader*>(&quad)};
  XrFrameEndInfo ei{XR_TYPE_FRAME_END_INFO};
  ei.displayTime = fs.predictedDisplayTime;
  ei.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  ei.layerCount = 2;
  ei.layers = layers;
  // A rectangle outside the image is rejected first.
  pv[1].subImage.imageRect = {{32, 0}, {64, 48}};
  EXPECT_EQ(xrEndFrame(sim.session, &ei), XR_ERROR_SWAPCHAIN_RECT_INVALID);
  pv[1].subImage.imageRect = {{0, 0}, {64, 48}};
  ASSERT_EQ(xrEndFrame(sim.session, &ei), XR_SUCCESS);
  vkDestroyCommandPool(sim.vk_device, pool, nullptr);

  const auto check = [&](const char* eye, int r, int g, int b, int width = 64, int height = 48) {
    const std::string file = dir + "/frame_000000_" + eye + ".png";
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    int w = 0, h = 0, c = 0;
    unsigned char* px = stbi_load(file.c_str(), &w, &h, &c, 4);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(w, width);
    EXPECT_EQ(h, height);
    EXPECT_EQ(px[0], r);
    EXPECT_EQ(px[1], g);
    EXPECT_EQ(px[2], b);
    stbi_image_free(px);
  };
  check("left", 255, 0, 0);
  check("right", 0, 0, 255);
  check("quad0", 0, 0, 255, 16, 8);
}

}  // namespace
