// Reading glTF accessors (tinygltf model) into flat arrays, with every bound checked before any
// allocation: buffer views inside their buffers, elements inside their views, strides, sparse
// substitutions, counts against Limits. Thread-safety: const use of an immutable tinygltf::Model.
#pragma once

#include "draco_decode.hpp"
#include "pushpull/assets/model.hpp"

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::assets::detail {

struct AccessorReader {
  const tinygltf::Model& gltf;
  const std::string& name;  // the file, for messages
  const Limits& limits;

  // Throws AssetError "NAME: accessor N: WHAT".
  [[noreturn]] void fail(int accessor, const std::string& what) const;

  static int component_size(int component_type);  // bytes, 0 for an unknown type
  // One component as a double, normalized integers mapped to [0, 1] or [-1, 1].
  static double component_value(const unsigned char* p, int component_type, bool normalized);

  // The first of `count` elements of `element_size` bytes at `offset` in buffer view `view_index`,
  // and the effective stride (the view's byteStride when allow_stride, else packed); checks bounds.
  std::pair<const unsigned char*, std::size_t> view_bytes(int accessor, int view_index, std::uint64_t offset,
                                                          std::uint64_t count, std::uint64_t element_size,
                                                          bool allow_stride) const;

  const tinygltf::Accessor& accessor(int index) const;       // checked index and count
  FloatRows read_floats(int index) const;                    // #count by #components, sparse applied
  std::vector<std::uint32_t> read_indices(int index) const;  // SCALAR unsigned indices
};

}  // namespace pushpull::assets::detail
