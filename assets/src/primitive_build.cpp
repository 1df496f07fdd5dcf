#include "primitive_build.hpp"

#include "pushpull/assets/error.hpp"

#include <cmath>

namespace pushpull::assets::detail {

namespace {

void require_columns(const FloatRows& values, std::initializer_list<Eigen::Index> allowed,
                     const std::string& semantic, const std::string& where) {
  for (Eigen::Index c : allowed)
    if (values.cols() == c) return;
  throw AssetError(where + ": " + semantic + " has " + std::to_string(values.cols()) + " components");
}

}  // namespace

bool assign_attribute(Primitive& primitive, const std::string& semantic, FloatRows values,
                      const std::string& where) {
  if (semantic == "POSITION") {
    require_columns(values, {3}, semantic, where);
    primitive.positions = values;
  } else if (semantic == "NORMAL") {
    require_columns(values, {3}, semantic, where);
    primitive.normals = values;
    // Kept as read (not renormalized), so a written model can give unmoved vertices their bits
    // back; only normals that cannot be normalized at all are replaced.
    for (Eigen::Index i = 0; i < primitive.normals.rows(); ++i) {
      const float n = primitive.normals.row(i).norm();
      if (!std::isfinite(n) || n <= 1e-12f) primitive.normals.row(i) << 0.0f, 0.0f, 1.0f;
    }
  } else if (semantic == "TANGENT") {
    require_columns(values, {4}, semantic, where);
    primitive.tangents = values;
  } else if (semantic.rfind("TEXCOORD_", 0) == 0) {
    require_columns(values, {2}, semantic, where);
    const std::string digits = semantic.substr(9);
    if (digits.empty() || digits.size() > 2 || digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    const std::size_t set = std::stoul(digits);
    if (primitive.texcoords.size() <= set) primitive.texcoords.resize(set + 1);
    primitive.texcoords[set] = values;
  } else if (semantic == "COLOR_0") {
    require_columns(values, {3, 4}, semantic, where);
    primitive.colors.resize(values.rows(), 4);
    primitive.colors.leftCols(3) = values.leftCols(3);
    if (values.cols() == 4)
      primitive.colors.col(3) = values.col(3);
    else
      primitive.colors.col(3).setOnes();
  } else {
    return false;
  }
  return true;
}

void assign_triangles(Primitive& primitive, int mode, std::vector<std::uint32_t> indices, bool indexed,
                      const std::string& where) {
  const auto vertex_count = static_cast<std::uint64_t>(primitive.positions.rows());
  if (!indexed) {
    indices.resize(vertex_count);
    for (std::uint32_t i = 0; i < vertex_count; ++i) indices[i] = i;
  }
  for (std::uint32_t index : indices)
    if (index >= vertex_count)
      throw AssetError(where + ": index " + std::to_string(index) + " out of range (" +
                       std::to_string(vertex_count) + " vertices)");
  std::vector<std::uint32_t>& out = primitive.indices;
  out.clear();
  if (mode == 4) {
    if (indices.size() % 3 != 0) throw AssetError(where + ": triangle index count is not a multiple of 3");
    out = std::move(indices);
  } else if (mode == 5) {  // strip: alternate winding
    for (std::size_t i = 2; i < indices.size(); ++i) {
      if (i % 2 == 0)
        out.insert(out.end(), {indices[i - 2], indices[i - 1], indices[i]});
      else
        out.insert(out.end(), {indices[i - 1], indices[i - 2], indices[i]});
    }
  } else if (mode == 6) {  // fan
    for (std::size_t i = 2; i < indices.size(); ++i)
      out.insert(out.end(), {indices[i - 1], indices[i], indices[0]});
  } else {
    throw AssetError(where + ": primitive mode " + std::to_string(mode) + " is not triangles");
  }
}

void check_primitive(const Primitive& primitive, const std::string& where) {
  const Eigen::Index n = primitive.positions.rows();
  if (primitive.positions.cols() != 3 || (n == 0 && !primitive.indices.empty()))
    throw AssetError(where + ": no POSITION attribute");
  auto same = [&](Eigen::Index rows, const char* what) {
    if (rows != 0 && rows != n)
      throw AssetError(where + ": " + what + " has " + std::to_string(rows) + " values for " +
                       std::to_string(n) + " vertices");
  };
  same(primitive.normals.rows(), "NORMAL");
  same(primitive.tangents.rows(), "TANGENT");
  same(primitive.colors.rows(), "COLOR_0");
  for (const auto& uv : primitive.texcoords) same(uv.rows(), "TEXCOORD");
  if (!primitive.positions.allFinite()) throw AssetError(where + ": POSITION has non-finite values");
}

}  // namespace pushpull::assets::detail
