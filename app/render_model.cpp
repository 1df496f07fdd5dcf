#include "render_model.hpp"

#include "pushpull/deform/metrics.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/image_io.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace pushpull::app {
namespace {

bool has_extension(const assets::Material& m, const std::string& name) {
  return std::find(m.extensions.begin(), m.extensions.end(), name) != m.extensions.end();
}

// Decodes glTF textures on demand, once per (texture, colour space).
class TextureCache {
 public:
  TextureCache(const assets::Model& model, RenderModel& out) : model_(model), out_(out) {}
  int get(const assets::TextureRef& ref, bool srgb) {
    if (!ref.present() || ref.texture >= int(model_.textures.size())) return -1;
    const auto key = std::make_pair(ref.texture, srgb);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    int id = -1;
    const int image_index = model_.textures[size_t(ref.texture)].image;
    if (image_index >= 0 && image_index < int(model_.images.size())) {
      const assets::Image& image = model_.images[size_t(image_index)];
      if (!image.missing && !image.encoded.empty()) {
        try {
          out_.textures.push_back(renderer::decode_image(
              image.encoded, srgb, "image " + std::to_string(image_index) + " (" + image.name + ")"));
          id = int(out_.textures.size() - 1);
        } catch (const std::exception& e) {
          out_.warnings.push_back(e.what());
        }
      }
    }
    cache_[key] = id;
    return id;
  }

 private:
  const assets::Model& model_;
  RenderModel& out_;
  std::map<std::pair<int, bool>, int> cache_;
};

renderer::Material convert_material(const assets::Material& m, TextureCache& textures) {
  renderer::Material r;
  r.base_colour = {m.base_color_factor.x(), m.base_color_factor.y(), m.base_color_factor.z(),
                   m.base_color_factor.w()};
  r.metallic = m.metallic_factor;
  r.roughness = m.roughness_factor;
  r.emissive = {m.emissive_factor.x(), m.emissive_factor.y(), m.emissive_factor.z()};
  r.base_colour_texture = m.base_color_texture.texcoord == 0 ? textures.get(m.base_color_texture, true) : -1;
  r.metallic_roughness_texture =
      m.metallic_roughness_texture.texcoord == 0 ? textures.get(m.metallic_roughness_texture, false) : -1;
  r.normal_texture = m.normal_texture.texcoord == 0 ? textures.get(m.normal_texture, false) : -1;
  r.normal_scale = m.normal_texture.scale;
  r.occlusion_texture = m.occlusion_texture.texcoord == 0 ? textures.get(m.occlusion_texture, false) : -1;
  r.occlusion_strength = m.occlusion_texture.scale;
  r.emissive_texture = m.emissive_texture.texcoord == 0 ? textures.get(m.emissive_texture, true) : -1;
  r.double_sided = m.double_sided;
  // Extension factors are not decoded by assets: give clear-coated paint a full clear coat and
  // render transmissive glass as dark, glossy, opaque glass (no order-dependent transparency).
  if (has_extension(m, "KHR_materials_clearcoat")) {
    r.clearcoat = 1.0f;
    r.clearcoat_roughness = 0.03f;
  }
  if (has_extension(m, "KHR_materials_transmission") || m.alpha_mode == assets::AlphaMode::blend) {
    r.base_colour = {0.02f, 0.025f, 0.03f, 1.0f};
    r.base_colour_texture = -1;
    r.metallic = 0.0f;
    r.roughness = 0.05f;
  }
  return r;
}

// Vertex normals for a primitive without them: corners of faces whose normals differ by less than
// the crease angle share a vertex; `corner_vertex` gets the new vertex of each corner.
void split_at_creases(const std::vector<Eigen::Vector3f>& p, const std::vector<uint32_t>& indices,
                      double crease_deg, std::vector<uint32_t>& corner_to_original,
                      std::vector<Eigen::Vector3f>& normals, std::vector<uint32_t>& corner_vertex) {
  const size_t faces = indices.size() / 3;
  std::vector<Eigen::Vector3f> face_normal(faces);  // area-weighted
  for (size_t f = 0; f < faces; ++f)
    face_normal[f] =
        (p[indices[3 * f + 1]] - p[indices[3 * f]]).cross(p[indices[3 * f + 2]] - p[indices[3 * f]]);
  std::vector<std::vector<uint32_t>> corners_of(p.size());
  for (size_t c = 0; c < indices.size(); ++c) corners_of[indices[c]].push_back(uint32_t(c));
  const float cos_crease = float(std::cos(crease_deg * M_PI / 180.0));
  corner_vertex.assign(indices.size(), 0);
  for (uint32_t v = 0; v < p.size(); ++v) {
    std::vector<std::pair<Eigen::Vector3f, uint32_t>> clusters;  // representative unit normal, new vertex
    for (uint32_t c : corners_of[v]) {
      const Eigen::Vector3f n = face_normal[c / 3];
      // (stableNormalized: the squared norm of a huge model's face normal overflows a float: black pictures)
      const Eigen::Vector3f unit =
          n.cwiseAbs().maxCoeff() > 0 ? Eigen::Vector3f(n.stableNormalized()) : Eigen::Vector3f::UnitZ();
      bool placed = false;
      for (auto& [rep, vertex] : clusters)
        if (rep.dot(unit) >= cos_crease) {
          corner_vertex[c] = vertex;
          normals[vertex] += n;
          placed = true;
          break;
        }
      if (!placed) {
        const uint32_t vertex = uint32_t(corner_to_original.size());
        corner_to_original.push_back(v);
        normals.push_back(n);
        clusters.emplace_back(unit, vertex);
        corner_vertex[c] = vertex;
      }
    }
  }
  for (auto& n : normals)
    n = n.cwiseAbs().maxCoeff() > 0 ? Eigen::Vector3f(n.stableNormalized()) : Eigen::Vector3f::UnitZ();
}

}  // namespace

RenderModel build_render_model(const assets::Model& model, double crease_deg) {
  RenderModel out;
  TextureCache textures(model, out);
  for (const auto& m : model.materials) out.materials.push_back(convert_material(m, textures));
  renderer::RenderMesh& mesh = out.mesh;
  // The render frame's origin: the centre of the model frame's bounding box, in double.
  Eigen::AlignedBox3d box;
  for (const assets::Primitive& prim : model.primitives)
    for (Eigen::Index i = 0; i < prim.positions.rows(); ++i)
      box.extend(
          (prim.T_model_node * prim.positions.row(i).transpose().cast<double>().homogeneous()).head<3>());
  if (!box.isEmpty()) out.origin = box.center();

  for (const assets::Primitive& prim : model.primitives) {
    const Eigen::Matrix4d& T = prim.T_model_node;
    const Eigen::Matrix3d normal_matrix = T.topLeftCorner<3, 3>().inverse().transpose();
    const bool mirrored = T.topLeftCorner<3, 3>().determinant() < 0.0;
    const auto n_in = static_cast<size_t>(prim.vertex_count());
    std::vector<Eigen::Vector3f> world(n_in);
    for (size_t i = 0; i < n_in; ++i)
      world[i] =
          ((T * prim.positions.row(Eigen::Index(i)).transpose().cast<double>().homogeneous()).head<3>() -
           out.origin)
              .cast<float>();

    // Vertex list of this primitive after optional crease splitting.
    std::vector<uint32_t> to_original;
    std::vector<Eigen::Vector3f> normals;
    std::vector<uint32_t> local_indices = prim.indices;
    if (mirrored)
      for (size_t t = 0; t + 2 < local_indices.size(); t += 3)
        std::swap(local_indices[t + 1], local_indices[t + 2]);
    if (prim.normals.rows() == prim.vertex_count() && prim.vertex_count() > 0) {
      for (uint32_t i = 0; i < n_in; ++i) {
        to_original.push_back(i);
        normals.push_back(
            (normal_matrix * prim.normals.row(i).transpose().cast<double>()).normalized().cast<float>());
      }
    } else {
      std::vector<uint32_t> corner_vertex;
      split_at_creases(world, local_indices, crease_deg, to_original, normals, corner_vertex);
      local_indices = corner_vertex;
    }

    const uint32_t base = mesh.vertex_count();
    const bool has_uv = !prim.texcoords.empty() && prim.texcoords[0].rows() == prim.vertex_count();
    for (size_t k = 0; k < to_original.size(); ++k) {
      const uint32_t i = to_original[k];
      mesh.positions.insert(mesh.positions.end(), {world[i].x(), world[i].y(), world[i].z()});
      mesh.normals.insert(mesh.normals.end(), {normals[k].x(), normals[k].y(), normals[k].z()});
      if (has_uv)
        mesh.uvs.insert(mesh.uvs.end(), {prim.texcoords[0](i, 0), prim.texcoords[0](i, 1)});
      else
        mesh.uvs.insert(mesh.uvs.end(), {0.0f, 0.0f});
      out.deform_vertex.push_back(i < prim.deform_vertex.size() ? prim.deform_vertex[i] : -1);
    }
    const auto first = uint32_t(mesh.indices.size());
    for (uint32_t index : local_indices) mesh.indices.push_back(base + index);
    const int material = prim.material >= 0 && prim.material < int(out.materials.size()) ? prim.material : -1;
    mesh.submeshes.push_back({first, uint32_t(local_indices.size()), material});
  }
  out.file_normals = mesh.normals;
  return out;
}

std::vector<float> render_positions(const RenderModel& render, const Eigen::MatrixXd& V) {
  std::vector<float> positions = render.mesh.positions;
  for (size_t r = 0; r < render.deform_vertex.size(); ++r) {
    const int d = render.deform_vertex[r];
    if (d < 0 || d >= V.rows()) continue;
    for (int c = 0; c < 3; ++c) positions[3 * r + size_t(c)] = float(V(d, c) - render.origin(c));
  }
  return positions;
}

std::vector<float> deformed_normals(const RenderModel& render, const std::vector<float>& deformed_positions) {
  const auto& indices = render.mesh.indices;
  const std::vector<float> before = renderer::compute_vertex_normals(render.mesh.positions, indices);
  const std::vector<float> after = renderer::compute_vertex_normals(deformed_positions, indices);
  std::vector<float> normals(render.file_normals.size());
  for (size_t v = 0; v + 2 < normals.size(); v += 3) {
    Eigen::Vector3f n(render.file_normals[v], render.file_normals[v + 1], render.file_normals[v + 2]);
    n += Eigen::Vector3f(after[v] - before[v], after[v + 1] - before[v + 1], after[v + 2] - before[v + 2]);
    n = n.cwiseAbs().maxCoeff() > 0 ? Eigen::Vector3f(n.stableNormalized())
                                    : Eigen::Vector3f(after[v], after[v + 1], after[v + 2]);
    normals[v] = n.x();
    normals[v + 1] = n.y();
    normals[v + 2] = n.z();
  }
  return normals;
}

std::vector<float> to_render_vertices(const RenderModel& render, const Eigen::VectorXd& values) {
  std::vector<float> out(render.deform_vertex.size(), 0.0f);
  for (size_t r = 0; r < out.size(); ++r) {
    const int d = render.deform_vertex[r];
    if (d >= 0 && d < values.size()) out[r] = float(values(d));
  }
  return out;
}

std::vector<float> curvature_signs_on_render_vertices(const RenderModel& render, const Eigen::MatrixXd& V,
                                                      const std::vector<std::int8_t>& signs,
                                                      double crease_deg) {
  const auto& indices = render.mesh.indices;
  // Render triangles whose three vertices map to deform vertices, in deform indices.
  std::vector<size_t> triangle_of_row;
  std::vector<Eigen::Vector3i> rows;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    Eigen::Vector3i f;
    bool mapped = true;
    for (int c = 0; c < 3; ++c) {
      const int d = render.deform_vertex[indices[t + size_t(c)]];
      mapped = mapped && d >= 0 && d < V.rows();
      f(c) = d;
    }
    if (!mapped) continue;
    rows.push_back(f);
    triangle_of_row.push_back(t);
  }
  Eigen::MatrixXi F(Eigen::Index(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k) F.row(Eigen::Index(k)) = rows[k].transpose();
  const std::vector<bool> flat = deform::flat_panel_faces(V, F, crease_deg * std::numbers::pi / 180.0);
  std::vector<bool> shown(render.deform_vertex.size(), false);
  for (size_t k = 0; k < rows.size(); ++k) {
    if (flat[k]) continue;
    for (int c = 0; c < 3; ++c) shown[indices[triangle_of_row[k] + size_t(c)]] = true;
  }
  std::vector<float> out(render.deform_vertex.size(), 0.0f);
  for (size_t r = 0; r < out.size(); ++r) {
    const int d = render.deform_vertex[r];
    if (shown[r] && d >= 0 && size_t(d) < signs.size()) out[r] = float(signs[size_t(d)]);
  }
  return out;
}

}  // namespace pushpull::app
