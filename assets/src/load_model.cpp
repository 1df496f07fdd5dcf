// load_model: reads the file under the size limit, dispatches on the extension, welds, sizes.
#include "pushpull/assets/model.hpp"

#include "draco_decode.hpp"
#include "gltf_loader.hpp"
#include "primitive_build.hpp"

#include <pushpull/deform/mesh_io.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace pushpull::assets {

namespace fs = std::filesystem;

namespace {

// Whether some triangle of the primitives has a non-zero area in the model frame (their node transforms
// applied): a model whose every triangle is degenerate in the file is named as such, not as welded away.
bool any_triangle_with_area(const std::vector<Primitive>& primitives) {
  for (const Primitive& p : primitives) {
    const Eigen::Matrix3d linear = p.T_model_node.topLeftCorner<3, 3>();
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
      const Eigen::Vector3d a = linear * p.positions.row(p.indices[t]).transpose().cast<double>(),
                            b = linear * p.positions.row(p.indices[t + 1]).transpose().cast<double>(),
                            c = linear * p.positions.row(p.indices[t + 2]).transpose().cast<double>();
      if ((b - a).cross(c - a).squaredNorm() > 0.0) return true;
    }
  }
  return false;
}

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

std::vector<std::uint8_t> read_file(const fs::path& path, const Limits& limits) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw AssetError(path.string() + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw AssetError(path.string() + ": not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw AssetError(path.string() + ": cannot read: " + ec.message());
  if (size > limits.max_file_bytes)
    throw AssetError(path.string() + ": " + std::to_string(size) + " bytes exceed the limit of " +
                     std::to_string(limits.max_file_bytes));
  std::vector<std::uint8_t> bytes(size);
  std::ifstream in(path, std::ios::binary);
  if (!in ||
      (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))))
    throw AssetError(path.string() + ": cannot read");
  return bytes;
}

void load_draco_file(std::span<const std::uint8_t> bytes, const std::string& name, const Limits& limits,
                     Model& model) {
  model.report.format = "Draco";
  detail::DecodedDraco decoded =
      detail::decode_draco(bytes, {}, name, limits.max_vertices, limits.max_triangles);
  Primitive primitive;
  primitive.name = fs::path(name).stem().string();
  for (auto& [semantic, values] : decoded.attributes)
    detail::assign_attribute(primitive, semantic, std::move(values), name);
  detail::assign_triangles(primitive, 4, std::move(decoded.indices), true, name);
  detail::check_primitive(primitive, name);
  model.primitives.push_back(std::move(primitive));
}

// OFF/OBJ/PLY through deform's reader: one primitive, and the deform mesh keeps double precision.
// A plain mesh's primitive: its positions relative to the centre of its bounding box, the centre in the node
// transform (double). Stored as floats, a mesh far from its file's origin (1e6 m: site or vehicle
// coordinates) lost its shape to their 24-bit mantissa (drawn torn, normals striped); relative to its centre
// it keeps it.
void set_centred_positions(Primitive& primitive, const Eigen::MatrixXd& V) {
  Eigen::AlignedBox3d box;
  for (Eigen::Index v = 0; v < V.rows(); ++v) box.extend(V.row(v).transpose());
  const Eigen::Vector3d centre =
      box.isEmpty() ? Eigen::Vector3d(Eigen::Vector3d::Zero()) : Eigen::Vector3d(box.center());
  primitive.positions = (V.rowwise() - centre.transpose()).cast<float>();
  primitive.T_model_node = Eigen::Matrix4d::Identity();
  primitive.T_model_node.topRightCorner<3, 1>() = centre;
}

void load_plain_mesh(std::span<const std::uint8_t> bytes, const std::string& name,
                     const std::string& extension, Model& model, deform::Mesh& exact) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  try {
    if (extension == ".off")
      exact = deform::parse_off(text, name);
    else if (extension == ".obj")
      exact = deform::parse_obj(text, name);
    else
      exact = deform::parse_ply(text, name);
  } catch (const deform::MeshIoError& e) {
    throw AssetError(e.what());
  }
  model.report.format = extension == ".off" ? "OFF" : extension == ".obj" ? "OBJ" : "PLY";
  Primitive primitive;
  primitive.name = fs::path(name).stem().string();
  // Drawn in 32-bit floats: a coordinate beyond their range (1e150 in an OFF) is named here, with its vertex,
  // instead of as the float positions' "non-finite values".
  for (Eigen::Index v = 0; v < exact.V.rows(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      if (!(std::abs(exact.V(v, axis)) <= double(std::numeric_limits<float>::max()))) {
        char text[160];
        std::snprintf(text, sizeof text,
                      ": vertex %lld has the coordinate %.6g, beyond the 32-bit floats it is drawn in (|x| < "
                      "3.4e38)",
                      static_cast<long long>(v), exact.V(v, axis));
        throw AssetError(name + text);
      }
  set_centred_positions(primitive, exact.V);
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(exact.F.size()));
  for (Eigen::Index f = 0; f < exact.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) indices.push_back(static_cast<std::uint32_t>(exact.F(f, c)));
  detail::assign_triangles(primitive, 4, std::move(indices), true, name);
  detail::check_primitive(primitive, name);
  model.primitives.push_back(std::move(primitive));
}

}  // namespace

std::vector<std::string> warnings_naming_the_file(const Model& model) {
  const std::string name = model.source_path.string() + ":";
  std::vector<std::string> named;
  for (const std::string& warning : model.report.warnings)
    named.push_back(warning.rfind(name, 0) == 0 ? warning : name + " " + warning);
  return named;
}

bool is_supported_model_path(const fs::path& path) {
  const std::string e = lower_extension(path);
  return e == ".gltf" || e == ".glb" || e == ".drc" || e == ".off" || e == ".obj" || e == ".ply";
}

Model load_model_from_memory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                             const fs::path& base_dir, const LoadOptions& options) {
  const std::string extension = lower_extension(name);
  if (!is_supported_model_path(name))
    throw AssetError(name + ": unsupported model format '" + extension +
                     "' (expected .gltf, .glb, .drc, .off, .obj or .ply)");
  if (bytes.size() > options.limits.max_file_bytes) throw AssetError(name + ": file exceeds the size limit");
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    throw AssetError("scale must be a positive number");
  if (options.target_length_m &&
      (!(*options.target_length_m > 0.0) || !std::isfinite(*options.target_length_m)))
    throw AssetError("target length must be a positive number of metres");

  Model model;
  model.source_path = name;
  deform::Mesh exact;
  const std::span<const std::uint8_t> data(bytes);
  if (extension == ".gltf" || extension == ".glb")
    detail::load_gltf(data, name, base_dir, options.limits, options.refuse_unsupported_required, model);
  else if (extension == ".drc")
    load_draco_file(data, name, options.limits, model);
  else
    load_plain_mesh(data, name, extension, model, exact);

  // In the model frame, after the nodes' transforms (a node translated by 1e308 put a glTF's vertices there,
  // drawn as nothing, welded into one point): beyond the 32-bit floats the model is drawn in.
  for (const Primitive& p : model.primitives)
    for (Eigen::Index v = 0; v < p.positions.rows(); ++v) {
      const Eigen::Vector3d at =
          p.T_model_node.topLeftCorner<3, 3>() * p.positions.row(v).transpose().cast<double>() +
          p.T_model_node.topRightCorner<3, 1>();
      for (int axis = 0; axis < 3; ++axis)
        if (!(std::abs(at(axis)) <= double(std::numeric_limits<float>::max()))) {
          char coordinate[32];
          std::snprintf(coordinate, sizeof coordinate, "%.6g", at(axis));
          throw AssetError(
              name + ": vertex " + std::to_string(v) + " of primitive \"" + p.name +
              "\" (node/mesh#primitive) has the coordinate " + coordinate +
              " in the model frame (its node's transform applied), beyond the 32-bit floats it is "
              "drawn in (|x| < 3.4e38)");
        }
    }
  // A mesh file is welded on the reader's doubles (weld_primitives keeps them in the deform mesh).
  model.report.weld = weld_primitives(model.primitives, options.weld, model.deform_mesh,
                                      exact.V.rows() > 0 ? &exact.V : nullptr);
  if (model.deform_mesh.F.rows() == 0) {
    if (model.report.weld.collapsed_triangles > 0 && !any_triangle_with_area(model.primitives))
      throw AssetError(
          name + ": every triangle (" + std::to_string(model.report.weld.collapsed_triangles) +
          ") has zero area in the file itself (repeated corners, coincident or collinear points, or a "
          "node scaled to zero): nothing to draw or deform");
    if (model.report.weld.collapsed_triangles > 0)  // there were some: the weld's tolerance took them all
      throw AssetError(name + ": welding collapsed every triangle (" +
                       std::to_string(model.report.weld.collapsed_triangles) +
                       "): the weld tolerance is too large for this model");
    throw AssetError(name + ": the model has no triangles");
  }
  // Triangles that survive the weld but all have zero area (collinear corners) leave nothing to draw or
  // deform either: render drew nothing and blamed the model's scale.
  if (!any_triangle_with_area(model.primitives))
    throw AssetError(name + ": every triangle (" + std::to_string(model.deform_mesh.F.rows()) +
                     ") has zero area in the file itself (collinear or coincident corners): nothing to draw "
                     "or deform");
  for (Eigen::Index v = 0; v < model.deform_mesh.V.rows(); ++v)
    model.bounds.extend(model.deform_mesh.V.row(v).transpose());

  model.scale = options.scale;
  if (options.target_length_m) {
    const double longest = model.bounds.sizes().maxCoeff();
    if (!(longest > 0.0))
      throw AssetError(name + ": the model has zero size; cannot scale it to a target length");
    model.scale = *options.target_length_m / longest;
  }
  return model;
}

Model model_from_mesh(const deform::Mesh& mesh, const std::string& name) {
  if (mesh.V.cols() != 3 || mesh.F.cols() != 3) throw AssetError(name + ": mesh must be #V by 3 and #F by 3");
  Model model;
  model.source_path = name;
  model.report.format = "mesh";
  Primitive primitive;
  primitive.name = name;
  set_centred_positions(primitive, mesh.V);
  std::vector<std::uint32_t> indices;
  indices.reserve(static_cast<std::size_t>(mesh.F.size()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      if (mesh.F(f, c) < 0 || mesh.F(f, c) >= mesh.V.rows())
        throw AssetError(name + ": face index out of range");
      indices.push_back(static_cast<std::uint32_t>(mesh.F(f, c)));
    }
  detail::assign_triangles(primitive, 4, std::move(indices), true, name);
  detail::check_primitive(primitive, name);
  primitive.deform_vertex.resize(static_cast<std::size_t>(mesh.V.rows()));
  for (std::size_t v = 0; v < primitive.deform_vertex.size(); ++v)
    primitive.deform_vertex[v] = static_cast<int>(v);
  model.primitives.push_back(std::move(primitive));
  model.deform_mesh = mesh;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) model.bounds.extend(mesh.V.row(v).transpose());
  model.report.weld.render_vertices = model.report.weld.deform_vertices =
      static_cast<std::size_t>(mesh.V.rows());
  model.report.weld.render_triangles = model.report.weld.deform_triangles =
      static_cast<std::size_t>(mesh.F.rows());
  model.report.weld.topology = analyze_topology(mesh);
  return model;
}

Model load_model(const fs::path& path, const LoadOptions& options) {
  const std::string extension = lower_extension(path);
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw AssetError(path.string() +
                     ": is a folder, not a model file (.gltf, .glb, .drc, .off, .obj or .ply)");
  if (!is_supported_model_path(path))
    throw AssetError(path.string() + ": unsupported model format '" + extension +
                     "' (expected .gltf, .glb, .drc, .off, .obj or .ply)");
  const std::vector<std::uint8_t> bytes = read_file(path, options.limits);
  fs::path base = path.parent_path();
  if (base.empty()) base = ".";
  Model model = load_model_from_memory(bytes, path.string(), base, options);
  model.source_path = path;
  model.source_files.insert(model.source_files.begin(), path);
  return model;
}

}  // namespace pushpull::assets
