// Renderer: resources (textures, materials, meshes), per-frame slots and the frame recording.
#include "pushpull/renderer/renderer.hpp"

#include "gpu_mesh.hpp"
#include "gpu_resources.hpp"
#include "pipelines.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/vk_check.hpp"
#include "textures.hpp"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

namespace pushpull::renderer {

using namespace detail;

namespace {

constexpr uint32_t kMaxMaterials = 4096;

// What one pass of a frame records into: its own command buffer (its own submission batch, so a pass that
// waits for a window's image does not hold back the others) and its own FrameDataGpu (views, lighting).
struct PassResources {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  Buffer frame_data;  // FrameDataGpu, host visible
  VkDescriptorSet frame_set = VK_NULL_HANDLE;
};

struct FrameSlot {
  UniqueCommandPool pool;
  UniqueFence fence;  // signalled when the GPU finished the frame that last used this slot (all its passes)
  std::array<PassResources, Renderer::kMaxPasses> passes;
};

struct GpuMaterial {
  Buffer params;  // MaterialGpu
  VkDescriptorSet set = VK_NULL_HANDLE;
};

struct Attachments {
  VkExtent2D extent{};
  Image depth;
  Image msaa_colour;  // when samples > 1
  VkFormat colour_format = VK_FORMAT_UNDEFINED;
};

struct PipelinePair {
  UniquePipeline mesh;
  UniquePipeline mesh_on_top;
  UniquePipeline overlay;
  // One sample, no depth attachment: meshes and the legend over a copied image (made when first needed).
  UniquePipeline over_copy;
  UniquePipeline overlay_over_copy;
};

// A pass's uniform data: its views, the studio lighting, the colour-map settings.
FrameDataGpu frame_data(std::span<const View> views, const FrameSettings& settings) {
  FrameDataGpu data{};
  for (size_t i = 0; i < views.size(); ++i) {
    data.views[i].view_projection = views[i].projection * views[i].view;
    data.views[i].eye_world = glm::vec4(glm::vec3(glm::inverse(views[i].view)[3]), 1.0f);
  }
  const glm::vec3 up = glm::normalize(settings.up);
  // Key light from above, front-left of the first view.
  const glm::mat3 R_world_eye = glm::transpose(glm::mat3(views[0].view));
  const glm::vec3 key = glm::normalize(R_world_eye * glm::vec3(-0.4f, 0.0f, 0.6f) + up * 1.2f);
  data.up_world = glm::vec4(up, 0.0f);
  data.key_light_dir = glm::vec4(key, 0.0f);
  data.colour_params = {settings.scalar_max, settings.curvature_epsilon, settings.exposure,
                        settings.show_overlays ? 1.0f : 0.0f};
  data.mode = {static_cast<uint32_t>(settings.color_mode), settings.lighting ? 1u : 0u, 0u, 0u};
  return data;
}

}  // namespace

struct Renderer::Impl {
  const Context& context;
  RendererOptions options;
  std::thread::id owner = std::this_thread::get_id();

  PipelineLayouts layouts;
  std::map<VkFormat, PipelinePair> pipelines;
  UniqueDescriptorPool descriptor_pool;
  UniqueSampler sampler;
  UniqueSampler clamp_sampler;

  std::vector<FrameSlot> slots;
  uint64_t frame_index = 0;  // frames submitted so far; the frame being built uses slot frame_index % N

  std::vector<Image> textures;
  TextureId white_texture = 0;
  TextureId flat_normal_texture = 0;
  std::vector<GpuMaterial> materials;
  MaterialId default_material = 0;
  std::vector<GpuMesh> meshes;
  std::vector<std::unique_ptr<Attachments>> attachment_sets;  // most recently used first

  std::optional<Image> legend;
  VkDescriptorSet legend_set = VK_NULL_HANDLE;
  glm::vec4 legend_rect{0.0f};
  std::optional<Buffer> legend_staging;  // a new legend's pixels: the next frame records their upload
  // Resources replaced while frames in flight may still read them (a legend changes during a drag: no
  // vkDeviceWaitIdle): freed once every frame submitted before `frame` has finished.
  struct Retired {
    uint64_t frame = 0;  // frame_index when retired: frames < frame may use it
    std::optional<Image> image;
    std::optional<Buffer> buffer;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  std::vector<Retired> retired;
  uint64_t last_upload_bytes = 0;

  explicit Impl(const Context& c, const RendererOptions& o) : context(c), options(o) {}

  void assert_owner() const {
    assert(std::this_thread::get_id() == owner && "pushpull::renderer::Renderer used from a second thread");
    if (std::this_thread::get_id() != owner)
      throw std::logic_error("pushpull::renderer::Renderer used from a thread other than its creator");
  }

  [[nodiscard]] uint32_t slot_index() const { return static_cast<uint32_t>(frame_index % slots.size()); }

  VkDescriptorSet allocate_set(VkDescriptorSetLayout layout) {
    VkDescriptorSetAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    info.descriptorPool = descriptor_pool.get();
    info.descriptorSetCount = 1;
    info.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    PP_VK_CHECK(vkAllocateDescriptorSets(context.device(), &info, &set));
    return set;
  }

  void wait_slot(uint32_t slot) {
    VkFence fence = slots[slot].fence.get();
    PP_VK_CHECK(vkWaitForFences(context.device(), 1, &fence, VK_TRUE, UINT64_MAX));
  }

  // Frees retired resources whose users (frames < their `frame`) have all finished: every frame before
  // `frames_finished` has been waited for.
  void release_retired(uint64_t frames_finished) {
    std::erase_if(retired, [&](Retired& x) {
      if (x.frame > frames_finished) return false;
      if (x.set != VK_NULL_HANDLE)
        PP_VK_CHECK(vkFreeDescriptorSets(context.device(), descriptor_pool.get(), 1, &x.set));
      return true;
    });
  }

  PipelinePair& pipelines_for(VkFormat format) {
    auto it = pipelines.find(format);
    if (it != pipelines.end()) return it->second;
    PipelinePair pair;
    pair.mesh = create_mesh_pipeline(context, layouts.mesh.get(), format, options.samples);
    pair.mesh_on_top = create_mesh_pipeline(context, layouts.mesh.get(), format, options.samples, false);
    pair.overlay = create_overlay_pipeline(context, layouts.overlay2d.get(), format, options.samples);
    return pipelines.emplace(format, std::move(pair)).first->second;
  }

  // One depth (+ MSAA colour) set per target size and format, kept while in use: a loop that draws the eyes
  // and a mirror window of another size switches sets without waiting for the GPU. Only when more than
  // kMaxAttachmentSets sizes are in play (a window being resized) is the least recently used set dropped,
  // after waiting for the GPU to finish with it.
  static constexpr size_t kMaxAttachmentSets = 4;
  Attachments& ensure_attachments(VkExtent2D extent, VkFormat colour_format) {
    for (size_t i = 0; i < attachment_sets.size(); ++i) {
      Attachments& a = *attachment_sets[i];
      if (a.extent.width == extent.width && a.extent.height == extent.height &&
          a.colour_format == colour_format) {
        std::rotate(attachment_sets.begin(), attachment_sets.begin() + long(i),
                    attachment_sets.begin() + long(i) + 1);
        return *attachment_sets.front();  // most recently used first
      }
    }
    if (attachment_sets.size() >= kMaxAttachmentSets) {
      PP_VK_CHECK(vkDeviceWaitIdle(context.device()));  // the dropped set may still be in use
      attachment_sets.pop_back();
    }
    auto created = std::make_unique<Attachments>();
    Attachments& attachments = *created;
    attachments.extent = extent;
    attachments.colour_format = colour_format;
    ImageDesc depth;
    depth.extent = extent;
    depth.format = kDepthFormat;
    depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    depth.samples = options.samples;
    depth.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    attachments.depth = create_image(context, depth);
    if (options.samples != VK_SAMPLE_COUNT_1_BIT) {
      ImageDesc colour;
      colour.extent = extent;
      colour.format = colour_format;
      colour.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      colour.samples = options.samples;
      attachments.msaa_colour = create_image(context, colour);
    }
    attachment_sets.insert(attachment_sets.begin(), std::move(created));
    return attachments;
  }

  void write_material_set(GpuMaterial& gpu, const Material& material) {
    auto texture_view = [&](int id, TextureId fallback) {
      if (id < 0) return textures[fallback].view.get();
      if (static_cast<size_t>(id) >= textures.size())
        throw std::invalid_argument("material refers to texture " + std::to_string(id) +
                                    " that was never added");
      return textures[static_cast<size_t>(id)].view.get();
    };
    VkDescriptorBufferInfo buffer_info{gpu.params.buffer.get(), 0, sizeof(MaterialGpu)};
    std::array<VkDescriptorImageInfo, 5> images{
        VkDescriptorImageInfo{sampler.get(), texture_view(material.base_colour_texture, white_texture),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        VkDescriptorImageInfo{sampler.get(), texture_view(material.metallic_roughness_texture, white_texture),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        VkDescriptorImageInfo{sampler.get(), texture_view(material.normal_texture, flat_normal_texture),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        VkDescriptorImageInfo{sampler.get(), texture_view(material.occlusion_texture, white_texture),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        VkDescriptorImageInfo{sampler.get(), texture_view(material.emissive_texture, white_texture),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    std::array<VkWriteDescriptorSet, 6> writes{};
    for (uint32_t i = 0; i < writes.size(); ++i) {
      writes[i] = {};
      writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[i].dstSet = gpu.set;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      if (i == 0) {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        writes[i].pBufferInfo = &buffer_info;
      } else {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[i].pImageInfo = &images[i - 1];
      }
    }
    vkUpdateDescriptorSets(context.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  }

  // Copies `from` (COLOR_ATTACHMENT_OPTIMAL before and after) into `to`, scaled to cover it, centred; leaves
  // `to` in its final layout, or in COLOR_ATTACHMENT_OPTIMAL ready to be drawn over when `drawn_over`.
  void record_blit(VkCommandBuffer cmd, const ColorTarget& from, VkExtent2D from_extent,
                   const ColorTarget& to, VkExtent2D to_extent, bool drawn_over);
  // Draws `draws` over the contents of `target` (COLOR_ATTACHMENT_OPTIMAL), one sample, no depth, in draw
  // order, then the legend when the settings show it; leaves the target in its final layout.
  void record_over_copy(VkCommandBuffer cmd, PipelinePair& pipes, VkFormat format, const ColorTarget& target,
                        VkExtent2D extent, std::span<const Draw> draws, const FrameSettings& settings,
                        VkDescriptorSet frame_set);
  // The colour-map legend (set_legend) with the given overlay pipeline, inside a begun rendering.
  void record_legend(VkCommandBuffer cmd, VkPipeline pipeline);
  // Begins rendering into `colour` (and `depth`, if not null) over the whole extent, sets the viewport and
  // scissor to it and binds the pass's frame data as set 0 of the mesh pipelines.
  void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, const VkRenderingAttachmentInfo& colour,
                       const VkRenderingAttachmentInfo* depth, VkDescriptorSet frame_set);
  // Binds and draws meshes in the given order with the pipeline `pipeline_of` picks (set 0 = frame_set
  // bound).
  template <class PipelineOf>
  void record_draws(VkCommandBuffer cmd, std::span<const Draw* const> ordered, uint32_t view_index,
                    PipelineOf pipeline_of);
  void record_view(VkCommandBuffer cmd, const PipelinePair& pipes, const ColorTarget& target,
                   VkExtent2D extent, uint32_t view_index, std::span<const Draw> draws,
                   const FrameSettings& settings, VkDescriptorSet frame_set, const Attachments& attachments);
};

Renderer::Renderer(const Context& context, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(context, options)) {
  Impl& r = *impl_;
  if (options.frames_in_flight == 0)
    throw std::invalid_argument("RendererOptions::frames_in_flight must be >= 1");
  {
    // A sample count the device cannot render (lavapipe: 1 and 4) drew noise without an error: refused here,
    // with the counts it has.
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    const VkSampleCountFlags supported =
        limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
    const auto bits = static_cast<VkSampleCountFlags>(options.samples);
    if (bits == 0 || (bits & (bits - 1)) != 0 || (supported & bits) == 0) {
      std::string counts;
      for (VkSampleCountFlags b = 1; b <= VK_SAMPLE_COUNT_64_BIT; b <<= 1)
        if (supported & b) counts += (counts.empty() ? "" : ", ") + std::to_string(b);
      throw std::invalid_argument("MSAA with " + std::to_string(bits) + " samples: " +
                                  context.properties().deviceName + " renders " + counts + " samples");
    }
  }
  VkDevice device = context.device();
  r.layouts = create_pipeline_layouts(context);
  r.sampler = create_sampler(context, VK_SAMPLER_ADDRESS_MODE_REPEAT);
  r.clamp_sampler = create_sampler(context, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);

  const std::array<VkDescriptorPoolSize, 2> sizes{
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kMaxMaterials + 16},
      VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5 * kMaxMaterials + 16}};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = kMaxMaterials + 32;
  pool_info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  PP_VK_CHECK(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool));
  r.descriptor_pool = UniqueDescriptorPool(device, pool);

  r.slots.resize(options.frames_in_flight);
  for (FrameSlot& slot : r.slots) {
    slot.pool = create_command_pool(context, VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT);
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = slot.pool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkFenceCreateInfo fi{};
    fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fence = VK_NULL_HANDLE;
    PP_VK_CHECK(vkCreateFence(device, &fi, nullptr, &fence));
    slot.fence = UniqueFence(device, fence);
    for (PassResources& pass : slot.passes) {
      PP_VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &pass.cmd));
      pass.frame_data =
          create_buffer(context, sizeof(FrameDataGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
      pass.frame_set = r.allocate_set(r.layouts.frame.get());
      VkDescriptorBufferInfo buffer_info{pass.frame_data.buffer.get(), 0, sizeof(FrameDataGpu)};
      VkWriteDescriptorSet write{};
      write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      write.dstSet = pass.frame_set;
      write.dstBinding = 0;
      write.descriptorCount = 1;
      write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      write.pBufferInfo = &buffer_info;
      vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
    }
  }

  TextureRGBA8 white{1, 1, {255, 255, 255, 255}, false};
  r.white_texture = add_texture(white);
  TextureRGBA8 flat{1, 1, {128, 128, 255, 255}, false};
  r.flat_normal_texture = add_texture(flat);
  r.default_material = add_material(Material{});
}

Renderer::~Renderer() {
  if (impl_) vkDeviceWaitIdle(impl_->context.device());  // no throw from a destructor
}

TextureId Renderer::add_texture(const TextureRGBA8& texture) {
  impl_->assert_owner();
  impl_->textures.push_back(upload_texture(impl_->context, texture));
  return static_cast<TextureId>(impl_->textures.size() - 1);
}

MaterialId Renderer::add_material(const Material& material) {
  Impl& r = *impl_;
  r.assert_owner();
  if (r.materials.size() >= kMaxMaterials) throw std::length_error("Renderer: more than 4096 materials");
  GpuMaterial gpu;
  gpu.params = create_buffer(r.context, sizeof(MaterialGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  MaterialGpu params{};
  params.base_colour = material.base_colour;
  params.emissive = glm::vec4(material.emissive, 0.0f);
  params.factors = {material.metallic, material.roughness, material.normal_scale, material.clearcoat};
  params.factors2 = {material.clearcoat_roughness, material.unlit ? 1.0f : 0.0f,
                     material.normal_texture >= 0 ? 1.0f : 0.0f, material.occlusion_strength};
  std::memcpy(gpu.params.mapped, &params, sizeof(params));
  gpu.set = r.allocate_set(r.layouts.material.get());
  r.write_material_set(gpu, material);
  r.materials.push_back(std::move(gpu));
  return static_cast<MaterialId>(r.materials.size() - 1);
}

MeshId Renderer::add_mesh(const RenderMesh& mesh, bool streamed) {
  Impl& r = *impl_;
  r.assert_owner();
  for (const auto& sub : mesh.submeshes)
    if (sub.material >= static_cast<int>(r.materials.size()))
      throw std::invalid_argument("RenderMesh submesh refers to material " + std::to_string(sub.material) +
                                  " that was never added");
  const uint32_t slots = static_cast<uint32_t>(r.slots.size());
  // Sets: one per frame in flight (the one being built included), one published and waiting, two writers.
  r.meshes.push_back(
      GpuMesh::create(r.context, mesh, streamed, slots, r.options.zero_copy_streaming ? slots + 3 : 0));
  return static_cast<MeshId>(r.meshes.size() - 1);
}

void Renderer::update_vertices(MeshId mesh, std::span<const float> positions, std::span<const float> normals,
                               std::span<const float> scalars, std::span<const OverlayWeights> overlays) {
  Impl& r = *impl_;
  r.assert_owner();
  if (mesh >= r.meshes.size()) throw std::invalid_argument("update_vertices: unknown mesh id");
  const uint32_t slot = r.slot_index();
  r.wait_slot(slot);  // the frame that used this staging slot N frames ago, not the one in flight
  GpuMesh& gpu = r.meshes[mesh];
  gpu.stage(slot, positions, normals, scalars, overlays);
  if (gpu.stream() && (!positions.empty() || !normals.empty() || !scalars.empty()))
    gpu.stream()->detach(r.frame_index);  // newer than any set published: the mesh's own buffers again
}

std::shared_ptr<VertexStream> Renderer::vertex_stream(MeshId mesh) const {
  impl_->assert_owner();
  if (mesh >= impl_->meshes.size()) throw std::invalid_argument("vertex_stream: unknown mesh id");
  return impl_->meshes[mesh].stream();
}

void Renderer::set_legend(std::optional<TextureRGBA8> legend, glm::vec4 rect) {
  Impl& r = *impl_;
  r.assert_owner();
  // Frames in flight may still sample the old legend: it is retired, not destroyed (no GPU wait). Many
  // changes between two frames (nothing drawn meanwhile) would pile up descriptor sets: then the queue is
  // drained.
  if (r.retired.size() >= 8) {
    PP_VK_CHECK(vkQueueWaitIdle(r.context.queue()));
    r.release_retired(r.frame_index);
  }
  if (r.legend || r.legend_set != VK_NULL_HANDLE)
    r.retired.push_back({r.frame_index, std::move(r.legend), std::move(r.legend_staging), r.legend_set});
  r.legend.reset();
  r.legend_staging.reset();
  r.legend_set = VK_NULL_HANDLE;
  if (!legend) return;
  StagedTexture staged = stage_texture(r.context, *legend);
  r.legend = std::move(staged.image);
  r.legend_staging = std::move(staged.staging);
  r.legend_rect = rect;
  r.legend_set = r.allocate_set(r.layouts.overlay.get());
  VkDescriptorImageInfo image{r.clamp_sampler.get(), r.legend->view.get(),
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = r.legend_set;
  write.dstBinding = 0;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = &image;
  vkUpdateDescriptorSets(r.context.device(), 1, &write, 0, nullptr);
}

template <class PipelineOf>
void Renderer::Impl::record_draws(VkCommandBuffer cmd, std::span<const Draw* const> ordered,
                                  uint32_t view_index, PipelineOf pipeline_of) {
  VkDescriptorSet bound_material = VK_NULL_HANDLE;
  VkPipeline bound_pipeline = VK_NULL_HANDLE;
  for (const Draw* draw_ptr : ordered) {
    const Draw& draw = *draw_ptr;
    if (draw.mesh >= meshes.size()) throw std::invalid_argument("render: unknown mesh id in a Draw");
    const VkPipeline pipeline = pipeline_of(draw);
    if (pipeline != bound_pipeline) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
      bound_pipeline = pipeline;
    }
    const GpuMesh& mesh = meshes[draw.mesh];
    DrawPushGpu push{draw.T_world_mesh, view_index, draw.colour_mapped ? 1u : 0u};
    vkCmdPushConstants(cmd, layouts.mesh.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    mesh.bind(cmd);
    for (const auto& sub : mesh.submeshes) {
      const VkDescriptorSet set =
          materials[sub.material < 0 ? default_material : static_cast<uint32_t>(sub.material)].set;
      if (set != bound_material) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.mesh.get(), 1, 1, &set, 0,
                                nullptr);
        bound_material = set;
      }
      vkCmdDrawIndexed(cmd, sub.index_count, 1, sub.first_index, 0, 0);
    }
  }
}

void Renderer::Impl::begin_rendering(VkCommandBuffer cmd, VkExtent2D extent,
                                     const VkRenderingAttachmentInfo& colour,
                                     const VkRenderingAttachmentInfo* depth, VkDescriptorSet frame_set) {
  VkRenderingInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &colour;
  rendering.pDepthAttachment = depth;
  vkCmdBeginRendering(cmd, &rendering);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.mesh.get(), 0, 1, &frame_set, 0,
                          nullptr);
}

void Renderer::Impl::record_legend(VkCommandBuffer cmd, VkPipeline pipeline) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts.overlay2d.get(), 0, 1, &legend_set, 0,
                          nullptr);
  vkCmdPushConstants(cmd, layouts.overlay2d.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::vec4),
                     &legend_rect);
  vkCmdDraw(cmd, 4, 1, 0, 0);
}

void Renderer::Impl::record_over_copy(VkCommandBuffer cmd, PipelinePair& pipes, VkFormat format,
                                      const ColorTarget& target, VkExtent2D extent,
                                      std::span<const Draw> draws, const FrameSettings& settings,
                                      VkDescriptorSet frame_set) {
  if (!pipes.over_copy)
    pipes.over_copy = create_mesh_pipeline(context, layouts.mesh.get(), format, VK_SAMPLE_COUNT_1_BIT,
                                           /*depth_test=*/false, /*depth_attachment=*/false);
  const bool legend = legend_set != VK_NULL_HANDLE && settings.show_legend;
  if (legend && !pipes.overlay_over_copy)
    pipes.overlay_over_copy = create_overlay_pipeline(context, layouts.overlay2d.get(), format,
                                                      VK_SAMPLE_COUNT_1_BIT, /*depth_attachment=*/false);
  VkRenderingAttachmentInfo colour{};
  colour.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  colour.imageView = target.view;
  colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the copied image stays under the draws
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  begin_rendering(cmd, extent, colour, nullptr, frame_set);
  std::vector<const Draw*> ordered;
  for (const Draw& draw : draws) ordered.push_back(&draw);
  record_draws(cmd, ordered, 0, [&](const Draw&) { return pipes.over_copy.get(); });
  if (legend) record_legend(cmd, pipes.overlay_over_copy.get());
  vkCmdEndRendering(cmd);
  image_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                target.final_layout, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                target.layer, 1);
}

void Renderer::Impl::record_view(VkCommandBuffer cmd, const PipelinePair& pipes, const ColorTarget& target,
                                 VkExtent2D extent, uint32_t view_index, std::span<const Draw> draws,
                                 const FrameSettings& settings, VkDescriptorSet frame_set,
                                 const Attachments& attachments) {
  const bool msaa = options.samples != VK_SAMPLE_COUNT_1_BIT;
  // Mesa 22.3 lavapipe resolves into layer 0 whatever the resolve view's base layer: resolve into
  // layers > 0 with vkCmdResolveImage after the pass (such targets need TRANSFER_DST usage).
  const bool explicit_resolve = msaa && target.layer != 0;
  // Our attachments: previous contents discarded; wait for earlier passes that used them.
  image_barrier(
      cmd, attachments.depth.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  if (msaa)
    image_barrier(cmd, attachments.msaa_colour.image.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                  VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  image_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, target.initial_layout,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, target.layer,
                1);

  VkRenderingAttachmentInfo colour{};

  colour.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colour.clearValue.color = {
      {settings.clear_colour.r, settings.clear_colour.g, settings.clear_colour.b, settings.clear_colour.a}};
  if (explicit_resolve) {
    colour.imageView = attachments.msaa_colour.view.get();
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  } else if (msaa) {
    colour.imageView = attachments.msaa_colour.view.get();
    colour.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    colour.resolveImageView = target.view;
    colour.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  } else {
    colour.imageView = target.view;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  }
  VkRenderingAttachmentInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  depth.imageView = attachments.depth.view.get();
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {1.0f, 0};

  begin_rendering(cmd, extent, colour, &depth, frame_set);
  // Depth-tested draws first, then the on-top ones.
  std::vector<const Draw*> ordered;
  for (const Draw& draw : draws)
    if (!draw.on_top) ordered.push_back(&draw);
  for (const Draw& draw : draws)
    if (draw.on_top) ordered.push_back(&draw);
  record_draws(cmd, ordered, view_index,
               [&](const Draw& draw) { return draw.on_top ? pipes.mesh_on_top.get() : pipes.mesh.get(); });
  if (legend_set != VK_NULL_HANDLE && settings.show_legend) record_legend(cmd, pipes.overlay.get());
  vkCmdEndRendering(cmd);

  VkImageLayout layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkPipelineStageFlags2 last_stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkAccessFlags2 last_access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  if (explicit_resolve) {
    image_barrier(cmd, attachments.msaa_colour.image.get(), VK_IMAGE_ASPECT_COLOR_BIT,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_RESOLVE_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    image_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_RESOLVE_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, target.layer, 1);
    VkImageResolve region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, target.layer, 1};
    region.extent = {extent.width, extent.height, 1};
    vkCmdResolveImage(cmd, attachments.msaa_colour.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      target.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    last_stage = VK_PIPELINE_STAGE_2_RESOLVE_BIT;
    last_access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  }
  if (target.final_layout != layout) {
    const bool to_transfer = target.final_layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    image_barrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, layout, target.final_layout, last_stage,
                  last_access, to_transfer ? VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT : VK_PIPELINE_STAGE_2_NONE,
                  to_transfer ? VK_ACCESS_2_TRANSFER_READ_BIT : VK_ACCESS_2_NONE, target.layer, 1);
  }
}

void Renderer::render(std::span<const View> views, std::span<const Draw> draws, const FrameSettings& settings,
                      const RenderTargets& targets, const FrameSync& sync) {
  const RenderPass pass{views, draws, settings, &targets, sync};
  render_frame(std::span(&pass, 1));
}

void Renderer::render_frame(std::span<const RenderPass> passes) {
  Impl& r = *impl_;
  r.assert_owner();
  if (passes.empty() || passes.size() > kMaxPasses)
    throw std::invalid_argument("render_frame: need 1 to " + std::to_string(kMaxPasses) + " passes");
  for (const RenderPass& pass : passes) {
    if (pass.targets == nullptr) throw std::invalid_argument("render_frame: a pass without targets");
    if (pass.blit_from != nullptr) {
      if (pass.targets->views.size() != 1 || pass.blit_from_extent.width == 0 ||
          pass.blit_from_extent.height == 0)
        throw std::invalid_argument("render_frame: a blit pass needs one target and a non-empty source");
      if (!pass.draws.empty() && pass.views.size() != 1)
        throw std::invalid_argument("render_frame: draws over a copied image need one view");
      continue;
    }
    if (pass.views.empty() || pass.views.size() > 2 || pass.targets->views.size() != pass.views.size())
      throw std::invalid_argument("render: need 1 or 2 views and as many colour targets");
    if (pass.targets->extent.width == 0 || pass.targets->extent.height == 0)
      throw std::invalid_argument("render: zero-sized target");
  }
  const uint32_t slot_id = r.slot_index();
  FrameSlot& slot = r.slots[slot_id];
  r.wait_slot(slot_id);
  // Every frame up to this slot's previous one has been waited for (each frame waits for its slot).
  const uint64_t frames_finished = r.frame_index >= r.slots.size() ? r.frame_index - r.slots.size() + 1 : 0;
  if (frames_finished > 0) r.release_retired(frames_finished);
  for (GpuMesh& mesh : r.meshes) mesh.begin_frame(r.frame_index, frames_finished);  // the sets it draws

  std::array<VkCommandBufferSubmitInfo, kMaxPasses> cmd_infos{};
  std::array<VkSemaphoreSubmitInfo, kMaxPasses> wait_infos{}, signal_infos{};
  std::array<VkSubmitInfo2, kMaxPasses> submits{};
  r.last_upload_bytes = 0;
  for (size_t p = 0; p < passes.size(); ++p) {
    const RenderPass& pass = passes[p];
    const RenderTargets& targets = *pass.targets;
    const FrameSettings& settings = pass.settings;
    PassResources& res = slot.passes[p];
    const Attachments* attachments = nullptr;
    PipelinePair* pipes = nullptr;
    const bool drawn_over = pass.blit_from != nullptr && !pass.draws.empty();
    if (pass.blit_from == nullptr) attachments = &r.ensure_attachments(targets.extent, targets.format);
    if (pass.blit_from == nullptr || drawn_over) {
      pipes = &r.pipelines_for(targets.format);
      const FrameDataGpu data = frame_data(pass.views, settings);
      std::memcpy(res.frame_data.mapped, &data, sizeof(data));
    }
    VkCommandBuffer cmd = res.cmd;
    PP_VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PP_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    if (p == 0) {  // the frame's uploads, once, before every pass (batches run in submission order)
      for (GpuMesh& mesh : r.meshes) r.last_upload_bytes += mesh.record_pending_uploads(cmd, slot_id);
      if (r.legend && r.legend_staging) {  // a new legend: its staging is freed once this frame has finished
        record_texture_upload(cmd, *r.legend, *r.legend_staging);
        r.retired.push_back({r.frame_index + 1, std::nullopt, std::move(r.legend_staging), VK_NULL_HANDLE});
        r.legend_staging.reset();
      }
    }
    if (pass.blit_from != nullptr) {
      r.record_blit(cmd, *pass.blit_from, pass.blit_from_extent, targets.views[0], targets.extent,
                    drawn_over);
      if (drawn_over)
        r.record_over_copy(cmd, *pipes, targets.format, targets.views[0], targets.extent, pass.draws,
                           settings, res.frame_set);
    } else {
      for (uint32_t v = 0; v < pass.views.size(); ++v)
        r.record_view(cmd, *pipes, targets.views[v], targets.extent, v, pass.draws, settings, res.frame_set,
                      *attachments);
    }
    PP_VK_CHECK(vkEndCommandBuffer(cmd));

    cmd_infos[p].sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
    wait_infos[p].sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
    wait_infos[p].semaphore = pass.sync.wait;
    wait_infos[p].stageMask = pass.blit_from != nullptr ? VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT
                                                        : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    cmd_infos[p].commandBuffer = res.cmd;
    signal_infos[p].sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
    signal_infos[p].semaphore = pass.sync.signal;
    signal_infos[p].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkSubmitInfo2& submit = submits[p];
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
    submit.waitSemaphoreInfoCount = pass.sync.wait != VK_NULL_HANDLE ? 1 : 0;
    submit.pWaitSemaphoreInfos = &wait_infos[p];
    submit.signalSemaphoreInfoCount = pass.sync.signal != VK_NULL_HANDLE ? 1 : 0;
    submit.pSignalSemaphoreInfos = &signal_infos[p];
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_infos[p];
  }
  // One submission, one fence for the slot: the fence's scope is every batch of this vkQueueSubmit2.
  VkFence fence = slot.fence.get();
  PP_VK_CHECK(vkResetFences(r.context.device(), 1, &fence));
  PP_VK_CHECK(vkQueueSubmit2(r.context.queue(), uint32_t(passes.size()), submits.data(), fence));
  ++r.frame_index;
}

bool Renderer::can_blit(VkFormat from, VkFormat to) const {
  VkFormatProperties a{}, b{};
  vkGetPhysicalDeviceFormatProperties(impl_->context.physical_device(), from, &a);
  vkGetPhysicalDeviceFormatProperties(impl_->context.physical_device(), to, &b);
  return (a.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT) != 0 &&
         (a.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0 &&
         (b.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
}

void Renderer::Impl::record_blit(VkCommandBuffer cmd, const ColorTarget& from, VkExtent2D from_extent,
                                 const ColorTarget& to, VkExtent2D to_extent, bool drawn_over) {
  // The source as drawn by an earlier pass of this frame; the target's old contents are discarded.
  image_barrier(cmd, from.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT, from.layer, 1);
  image_barrier(cmd, to.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, to.layer, 1);
  // Scale to cover the target, centred: the source's middle, cropped to the target's aspect.
  const double sw = from_extent.width, sh = from_extent.height, tw = to_extent.width, th = to_extent.height;
  double cw = sw, ch = sw * th / tw;
  if (ch > sh) ch = sh, cw = sh * tw / th;
  const int32_t x0 = int32_t(std::lround(0.5 * (sw - cw))), y0 = int32_t(std::lround(0.5 * (sh - ch)));
  VkImageBlit region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, from.layer, 1};
  region.srcOffsets[0] = {x0, y0, 0};
  region.srcOffsets[1] = {x0 + int32_t(std::lround(cw)), y0 + int32_t(std::lround(ch)), 1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, to.layer, 1};
  region.dstOffsets[0] = {0, 0, 0};
  region.dstOffsets[1] = {int32_t(to_extent.width), int32_t(to_extent.height), 1};
  vkCmdBlitImage(cmd, from.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to.image,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_LINEAR);
  image_barrier(cmd, from.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT,
                VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, from.layer,
                1);
  if (drawn_over)
    image_barrier(cmd, to.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, to.layer,
                  1);
  else
    image_barrier(cmd, to.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  to.final_layout, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, to.layer, 1);
}

void Renderer::wait_idle() {
  impl_->assert_owner();
  PP_VK_CHECK(vkDeviceWaitIdle(impl_->context.device()));
}

uint64_t Renderer::last_upload_bytes() const {
  return impl_->last_upload_bytes;
}

}  // namespace pushpull::renderer
