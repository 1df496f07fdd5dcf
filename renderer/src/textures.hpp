// Internal: sampled textures (RGBA8 with a full mip chain) and the shared sampler.
#pragma once

#include "gpu_resources.hpp"
#include "pushpull/renderer/types.hpp"

namespace pushpull::renderer::detail {

// A texture whose pixels are in a host-visible staging buffer, its image created but not yet written: the
// upload is recorded into a command buffer of the caller's (a frame's), so nothing waits for the GPU.
// Ownership: staging must outlive the GPU's execution of the recorded upload.
struct StagedTexture {
  Image image;
  Buffer staging;
};

// Creates the image (a full mip chain) and copies the pixels into staging. Throws std::invalid_argument when
// pixels.size() != width * height * 4 or the size is zero.
StagedTexture stage_texture(const Context& context, const TextureRGBA8& texture);

// Records staging -> level 0, mips by linear blits, and leaves the image SHADER_READ_ONLY_OPTIMAL for
// fragment shaders (commands later in submission order may sample it).
void record_texture_upload(VkCommandBuffer cmd, const Image& image, const Buffer& staging);

// stage_texture + record_texture_upload in a one-time submission, waited for (loading, not frames).
Image upload_texture(const Context& context, const TextureRGBA8& texture);

// Trilinear, repeat addressing (glTF default), max anisotropy off (not required by lavapipe).
UniqueSampler create_sampler(const Context& context, VkSamplerAddressMode address_mode);

}  // namespace pushpull::renderer::detail
