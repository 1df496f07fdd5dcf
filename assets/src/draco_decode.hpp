// Draco decoding (KHR_draco_mesh_compression payloads and raw .drc files) into flat arrays.
// Thread-safety: reentrant. Errors throw AssetError prefixed with `where`.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::assets::detail {

using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct DecodedDraco {
  std::size_t points = 0;                                     // vertices
  std::vector<std::pair<std::string, FloatRows>> attributes;  // glTF semantic -> #points by n
  std::vector<std::uint32_t> indices;                         // 3 per triangle
};

// attribute_ids: glTF semantic -> Draco unique id (from the extension); when empty, every named
// Draco attribute is returned under its glTF semantic (POSITION, NORMAL, TEXCOORD_0, COLOR_0).
DecodedDraco decode_draco(std::span<const std::uint8_t> bytes,
                          const std::vector<std::pair<std::string, int>>& attribute_ids,
                          const std::string& where, std::uint64_t max_vertices, std::uint64_t max_triangles);

}  // namespace pushpull::assets::detail
