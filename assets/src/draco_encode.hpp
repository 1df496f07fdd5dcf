// Draco re-compression of one written primitive (KHR_draco_mesh_compression). Sequential
// encoding keeps the point count and order, so accessor counts match the decoded data.
// Thread-safety: reentrant. Throws AssetError.
#pragma once

#include "pushpull/assets/scene.hpp"
#include "pushpull/assets/write.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::assets::detail {

struct DracoEncoded {
  std::vector<std::uint8_t> bytes;                                // the Draco bitstream
  std::vector<std::pair<std::string, int>> attribute_ids;         // glTF semantic -> Draco unique id
  std::vector<std::pair<std::string, nlohmann::json>> accessors;  // glTF accessors (no bufferView)
  nlohmann::json indices_accessor;
};

DracoEncoded encode_draco(const Primitive& primitive, const RowMatrixXf<3>& positions,
                          const RowMatrixXf<3>& normals, const RowMatrixXf<4>& tangents,
                          const WriteOptions& options);

}  // namespace pushpull::assets::detail
