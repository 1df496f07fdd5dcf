// Internal: sampled textures (RGBA8 with a full mip chain) and the shared sampler.
#pragma once

#include "gpu_resources.hpp"
#include "pushpull/renderer/types.hpp"

namespace pushpull::renderer::detail {

// Uploads pixels, generates mips by linear blits, leaves the image SHADER_READ_ONLY_OPTIMAL.
// Throws std::invalid_argument when pixels.size() != width * height * 4 or the size is zero.
Image upload_texture(const Context& context, const TextureRGBA8& texture);

// Trilinear, repeat addressing (glTF default), max anisotropy off (not required by lavapipe).
UniqueSampler create_sampler(const Context& context, VkSamplerAddressMode address_mode);

}  // namespace pushpull::renderer::detail
