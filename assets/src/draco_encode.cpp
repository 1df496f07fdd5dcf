#include "draco_encode.hpp"

#include "pushpull/assets/error.hpp"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

namespace pushpull::assets::detail {

namespace {

template <int Cols>
void add_attribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, const RowMatrixXf<Cols>& values,
                   const std::string& semantic, bool with_bounds, DracoEncoded& out) {
  draco::GeometryAttribute geometry;
  geometry.Init(type, nullptr, Cols, draco::DT_FLOAT32, false, sizeof(float) * Cols, 0);
  const int id = mesh.AddAttribute(geometry, true, static_cast<std::uint32_t>(values.rows()));
  draco::PointAttribute* attribute = mesh.attribute(id);
  for (Eigen::Index v = 0; v < values.rows(); ++v)
    attribute->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(v)),
                                 values.row(v).data());
  out.attribute_ids.emplace_back(semantic, static_cast<int>(attribute->unique_id()));
  static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
  nlohmann::json accessor = {{"componentType", 5126}, {"count", values.rows()}, {"type", kTypes[Cols]}};
  if (with_bounds && values.rows() > 0) {
    nlohmann::json min = nlohmann::json::array(), max = nlohmann::json::array();
    for (int c = 0; c < Cols; ++c) {
      min.push_back(static_cast<double>(values.col(c).minCoeff()));
      max.push_back(static_cast<double>(values.col(c).maxCoeff()));
    }
    accessor["min"] = min;
    accessor["max"] = max;
  }
  out.accessors.emplace_back(semantic, std::move(accessor));
}

}  // namespace

DracoEncoded encode_draco(const Primitive& primitive, const RowMatrixXf<3>& positions,
                          const RowMatrixXf<3>& normals, const RowMatrixXf<4>& tangents,
                          const WriteOptions& options) {
  DracoEncoded out;
  draco::Mesh mesh;
  mesh.set_num_points(static_cast<std::uint32_t>(positions.rows()));
  for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3)
    mesh.AddFace({draco::PointIndex(primitive.indices[t]), draco::PointIndex(primitive.indices[t + 1]),
                  draco::PointIndex(primitive.indices[t + 2])});
  add_attribute(mesh, draco::GeometryAttribute::POSITION, positions, "POSITION", true, out);
  if (normals.rows() > 0)
    add_attribute(mesh, draco::GeometryAttribute::NORMAL, normals, "NORMAL", false, out);
  if (tangents.rows() > 0)
    add_attribute(mesh, draco::GeometryAttribute::GENERIC, tangents, "TANGENT", false, out);
  for (std::size_t set = 0; set < primitive.texcoords.size(); ++set)
    if (primitive.texcoords[set].rows() > 0)
      add_attribute(mesh, draco::GeometryAttribute::TEX_COORD, primitive.texcoords[set],
                    "TEXCOORD_" + std::to_string(set), false, out);
  if (primitive.colors.rows() > 0)
    add_attribute(mesh, draco::GeometryAttribute::COLOR, primitive.colors, "COLOR_0", false, out);

  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  encoder.SetSpeedOptions(options.draco_speed, options.draco_speed);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.draco_position_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, options.draco_normal_bits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, options.draco_texcoord_bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!status.ok())
    throw AssetError(primitive.name + ": Draco encoding failed: " + status.error_msg_string());
  out.bytes.assign(buffer.data(), buffer.data() + buffer.size());
  const bool narrow = positions.rows() <= 65535;
  out.indices_accessor = {
      {"componentType", narrow ? 5123 : 5125}, {"count", primitive.indices.size()}, {"type", "SCALAR"}};
  return out;
}

}  // namespace pushpull::assets::detail
