// Converting a loaded model (pushpull::assets::Model) into renderer input, and deform-side per-vertex
// data (deformed positions, displacement, curvature sign, overlays) onto the render vertices.
//
// Frames: the RenderMesh is in the render frame: the model frame (every node transform applied, file units)
// shifted by -RenderModel::origin, so that floats keep their precision on a model that lies far from its
// file's origin (a part in site or vehicle coordinates); whoever draws it places it by translate(origin).
// Shapes: deform-side arrays have #Vd rows (Model::deform_mesh.V); render-side arrays #Vr entries.
// Thread-safety: pure functions on values.
#pragma once

#include "pushpull/assets/model.hpp"
#include "pushpull/renderer/types.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace pushpull::app {

struct RenderModel {
  renderer::RenderMesh mesh;  // one mesh, one submesh per primitive; positions relative to `origin`
  // The centre of the model's bounding box (model frame, file units): render frame = model frame - origin.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::vector<renderer::Material> materials;  // submesh material indices refer here; textures below
  std::vector<renderer::TextureRGBA8> textures;
  std::vector<int> deform_vertex;   // #Vr: row of deform_mesh.V, -1 when none
  std::vector<float> file_normals;  // #Vr*3: the normals drawn for the undeformed model
  std::vector<std::string> warnings;
};

// Flattens every primitive into the model frame. Primitives without normals are split at creases
// sharper than crease_deg (flat CAD faces stay flat, smooth surfaces stay smooth).
RenderModel build_render_model(const assets::Model& model, double crease_deg = 35.0);

// Render positions (render frame) from deform-side positions V (#Vd by 3, model frame); vertices without a
// deform vertex keep their undeformed position.
std::vector<float> render_positions(const RenderModel& render, const Eigen::MatrixXd& V);

// Normals for deformed render positions: the file normals rotated by how the surface turned
// (recomputed deformed minus recomputed undeformed), so undeformed regions keep their file normals.
std::vector<float> deformed_normals(const RenderModel& render, const std::vector<float>& deformed_positions);

// A deform-side per-vertex value (#Vd) on the render vertices (#Vr); 0 where unmapped.
std::vector<float> to_render_vertices(const RenderModel& render, const Eigen::VectorXd& per_deform_vertex);

// Curvature signs (#Vd, from deform::curvature_signs) on the render vertices (#Vr) as deform draws them
// (deform::display_curvature_signs, per render vertex): a render vertex shows its deform vertex's sign only
// if one of the render triangles using it is not a flat-panel face (deform::flat_panel_faces on the
// positions V, #Vd by 3, with the render crease angle), so coarse flat panels are drawn flat; 0 elsewhere.
std::vector<float> curvature_signs_on_render_vertices(const RenderModel& render, const Eigen::MatrixXd& V,
                                                      const std::vector<std::int8_t>& signs,
                                                      double crease_deg = 35.0);

}  // namespace pushpull::app
