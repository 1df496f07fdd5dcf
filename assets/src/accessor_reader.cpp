#include "accessor_reader.hpp"

#include "pushpull/assets/error.hpp"

#include <algorithm>
#include <cstring>

namespace pushpull::assets::detail {

void AccessorReader::fail(int accessor, const std::string& what) const {
  throw AssetError(name + ": accessor " + std::to_string(accessor) + ": " + what);
}

int AccessorReader::component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

double AccessorReader::component_value(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// Bytes of `count` elements of `element_size` at `offset` in buffer view `view_index`, with `stride`
// (0 = tightly packed); checks every bound. Returns the first byte and the effective stride.
std::pair<const unsigned char*, std::size_t> AccessorReader::view_bytes(int accessor, int view_index,
                                                                        std::uint64_t offset,
                                                                        std::uint64_t count,
                                                                        std::uint64_t element_size,
                                                                        bool allow_stride) const {
  if (view_index < 0 || view_index >= static_cast<int>(gltf.bufferViews.size()))
    fail(accessor, "bufferView " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = gltf.bufferViews[static_cast<std::size_t>(view_index)];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(gltf.buffers.size()))
    fail(accessor, "buffer " + std::to_string(view.buffer) + " does not exist");
  const auto& data = gltf.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail(accessor, "bufferView " + std::to_string(view_index) + " (byteOffset " +
                       std::to_string(view.byteOffset) + ", byteLength " + std::to_string(view.byteLength) +
                       ") runs past the end of buffer " + std::to_string(view.buffer) + " (" +
                       std::to_string(data.size()) + " bytes): corrupt bufferView lengths");
  std::uint64_t stride = element_size;
  if (allow_stride && view.byteStride != 0) {
    if (view.byteStride < element_size || view.byteStride > 252)
      fail(accessor, "invalid byteStride " + std::to_string(view.byteStride));
    stride = view.byteStride;
  }
  if (count > 0) {
    const std::uint64_t needed = offset + stride * (count - 1) + element_size;
    if (offset > view.byteLength || needed > view.byteLength)
      fail(accessor, std::to_string(count) + " elements need " + std::to_string(needed) +
                         " bytes, bufferView " + std::to_string(view_index) + " has " +
                         std::to_string(view.byteLength) + " (out of range)");
  }
  return {data.data() + view.byteOffset + offset, static_cast<std::size_t>(stride)};
}

const tinygltf::Accessor& AccessorReader::accessor(int index) const {
  if (index < 0 || index >= static_cast<int>(gltf.accessors.size())) fail(index, "does not exist");
  const tinygltf::Accessor& a = gltf.accessors[static_cast<std::size_t>(index)];
  if (a.count > limits.max_vertices * 3) fail(index, "absurd count " + std::to_string(a.count));
  return a;
}

FloatRows AccessorReader::read_floats(int index) const {
  const tinygltf::Accessor& a = accessor(index);
  const int columns = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const int size = component_size(a.componentType);
  if (columns < 1 || columns > 4 || size == 0)
    fail(index, "unsupported type/componentType for a vertex attribute");
  if (a.count > limits.max_vertices) fail(index, "absurd count " + std::to_string(a.count));
  const auto rows = static_cast<Eigen::Index>(a.count);
  const std::uint64_t element = static_cast<std::uint64_t>(size) * static_cast<std::uint64_t>(columns);
  if (a.bufferView < 0 && !a.sparse.isSparse) fail(index, "has neither bufferView nor sparse values");
  // Bounds first, allocation after: a count the data cannot back is refused without allocating.
  const auto [first, stride] = a.bufferView >= 0
                                   ? view_bytes(index, a.bufferView, a.byteOffset, a.count, element, true)
                                   : std::pair<const unsigned char*, std::size_t>{nullptr, 0};
  FloatRows out = FloatRows::Zero(rows, columns);
  if (a.bufferView >= 0) {
    for (Eigen::Index r = 0; r < rows; ++r)
      for (int c = 0; c < columns; ++c)
        out(r, c) = static_cast<float>(
            component_value(first + static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(c * size),
                            a.componentType, a.normalized));
  }
  if (a.sparse.isSparse) {
    const auto count = static_cast<std::uint64_t>(std::max(a.sparse.count, 0));
    if (count > a.count) fail(index, "sparse count exceeds count");
    const int index_size = component_size(a.sparse.indices.componentType);
    if (index_size == 0 || a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail(index, "bad sparse index type");
    auto [indices, index_stride] =
        view_bytes(index, a.sparse.indices.bufferView,
                   static_cast<std::uint64_t>(std::max(a.sparse.indices.byteOffset, 0)), count,
                   static_cast<std::uint64_t>(index_size), false);
    auto [values, value_stride] = view_bytes(
        index, a.sparse.values.bufferView,
        static_cast<std::uint64_t>(std::max(a.sparse.values.byteOffset, 0)), count, element, false);
    for (std::uint64_t k = 0; k < count; ++k) {
      const double target =
          component_value(indices + k * index_stride, a.sparse.indices.componentType, false);
      if (target < 0 || target >= static_cast<double>(a.count)) fail(index, "sparse index out of range");
      for (int c = 0; c < columns; ++c)
        out(static_cast<Eigen::Index>(target), c) = static_cast<float>(component_value(
            values + k * value_stride + static_cast<std::size_t>(c * size), a.componentType, a.normalized));
    }
  }
  return out;
}

std::vector<std::uint32_t> AccessorReader::read_indices(int index) const {
  const tinygltf::Accessor& a = accessor(index);
  if (a.type != TINYGLTF_TYPE_SCALAR || a.bufferView < 0)
    fail(index, "indices must be a SCALAR accessor with a bufferView");
  const int size = component_size(a.componentType);
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(index, "indices must be unsigned integers");
  auto [first, stride] =
      view_bytes(index, a.bufferView, a.byteOffset, a.count, static_cast<std::uint64_t>(size), false);
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i)
    out[i] = static_cast<std::uint32_t>(component_value(first + i * stride, a.componentType, false));
  return out;
}

}  // namespace pushpull::assets::detail
