#include "draco_decode.hpp"

#include "pushpull/assets/error.hpp"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

namespace pushpull::assets::detail {

namespace {

FloatRows read_attribute(const draco::PointAttribute& attribute, std::size_t points,
                         const std::string& what) {
  const int components = attribute.num_components();
  if (components < 1 || components > 4)
    throw AssetError(what + ": " + std::to_string(components) + " components");
  FloatRows out(static_cast<Eigen::Index>(points), components);
  for (std::size_t i = 0; i < points; ++i) {
    const auto value_index = attribute.mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
    if (value_index.value() >= attribute.size() ||
        !attribute.ConvertValue<float>(value_index, static_cast<std::int8_t>(components),
                                       out.row(static_cast<Eigen::Index>(i)).data()))
      throw AssetError(what + ": cannot read value of point " + std::to_string(i));
  }
  return out;
}

}  // namespace

DecodedDraco decode_draco(std::span<const std::uint8_t> bytes,
                          const std::vector<std::pair<std::string, int>>& attribute_ids,
                          const std::string& where, std::uint64_t max_vertices, std::uint64_t max_triangles) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) throw AssetError(where + ": corrupted Draco data: " + type.status().error_msg_string());
  if (type.value() != draco::TRIANGULAR_MESH)
    throw AssetError(where + ": Draco data is a point cloud, not a triangle mesh");
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok())
    throw AssetError(where + ": corrupted Draco data: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) throw AssetError(where + ": corrupted Draco data: no mesh");

  DecodedDraco out;
  out.points = mesh->num_points();
  if (out.points > max_vertices)
    throw AssetError(where + ": " + std::to_string(out.points) + " vertices exceed the limit");
  if (mesh->num_faces() > max_triangles)
    throw AssetError(where + ": " + std::to_string(mesh->num_faces()) + " triangles exceed the limit");
  out.indices.reserve(std::size_t{mesh->num_faces()} * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    const auto& face = mesh->face(f);
    for (int c = 0; c < 3; ++c) {
      if (face[c].value() >= out.points)
        throw AssetError(where + ": corrupted Draco data: index out of range");
      out.indices.push_back(face[c].value());
    }
  }

  if (!attribute_ids.empty()) {
    for (const auto& [semantic, id] : attribute_ids) {
      const draco::PointAttribute* attribute =
          id >= 0 ? mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id)) : nullptr;
      if (!attribute)
        throw AssetError(where + ": Draco data has no attribute with id " + std::to_string(id) + " (" +
                         semantic + ")");
      out.attributes.emplace_back(semantic, read_attribute(*attribute, out.points, where + ": " + semantic));
    }
  } else {
    const std::pair<draco::GeometryAttribute::Type, const char*> named[] = {
        {draco::GeometryAttribute::POSITION, "POSITION"},
        {draco::GeometryAttribute::NORMAL, "NORMAL"},
        {draco::GeometryAttribute::TEX_COORD, "TEXCOORD_0"},
        {draco::GeometryAttribute::COLOR, "COLOR_0"}};
    for (const auto& [type_id, semantic] : named) {
      if (const draco::PointAttribute* attribute = mesh->GetNamedAttribute(type_id))
        out.attributes.emplace_back(semantic,
                                    read_attribute(*attribute, out.points, where + ": " + semantic));
    }
  }
  return out;
}

}  // namespace pushpull::assets::detail
