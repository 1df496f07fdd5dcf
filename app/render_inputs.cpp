#include "render_inputs.hpp"

#include "commands.hpp"
#include "point_text.hpp"
#include "vertex_selection.hpp"

#include "pushpull/deform/surface_point.hpp"

#include <cstdint>
#include <cstdio>

namespace pushpull::app {
namespace {

Eigen::Vector3d vec3(const std::vector<double>& v, size_t offset = 0) {
  return {v[offset], v[offset + 1], v[offset + 2]};
}

}  // namespace

RenderInputs prepare_render_inputs(std::shared_ptr<const RenderModel> render, const deform::Mesh& rest,
                                   const Eigen::MatrixXd& V, bool deformed,
                                   const RenderCommandOptions& options, double life_size_scale,
                                   const assets::Model* model_file) {
  const Eigen::MatrixXd& V0 = rest.V;
  const Eigen::MatrixXi& F = rest.F;
  RenderInputs inputs;
  inputs.render = std::move(render);
  const RenderModel& model = *inputs.render;
  inputs.life_size_scale = life_size_scale;
  inputs.deformed = deformed;
  inputs.positions = render_positions(model, V);
  inputs.normals = deformed ? deformed_normals(model, inputs.positions) : model.file_normals;

  // Colour-map values, deform side -> render vertices.
  if (options.color == "displacement") {
    const Eigen::VectorXd magnitude = (V - V0).rowwise().norm();
    inputs.scalars = to_render_vertices(model, magnitude);
    inputs.scalar_max = magnitude.size() > 0 ? magnitude.maxCoeff() : 0.0;
  } else if (options.color == "curvature-sign") {
    // deform's one sign rule: flat when |K| L^2 <= dead-band, L = the model's bounding-box diagonal (the
    // same L and rule as `pushpull deform`'s metrics); flat panels drawn flat.
    const deform::GaussianCurvature after = deform::gaussian_curvature(V, F);
    const double threshold =
        deform::flat_curvature_threshold(deform::curvature_reference_length(V0), options.dead_band);
    std::vector<std::int8_t> signs = deform::curvature_signs(after, threshold);
    for (size_t i = 0; i < signs.size(); ++i)
      if (!after.defined_at(i)) signs[i] = 0;  // the boundary's turn, sheets meeting: not surface curvature
    inputs.scalars = curvature_signs_on_render_vertices(model, V, signs);
  } else if (options.color == "curvature-reversal") {
    // Where the sign reversed from rest to V (+ to -, - to +: the paper's sign changes, as deform's metrics
    // count them: the same rule, threshold and L), drawn in its new sign's colour; every other vertex "kept"
    // (0).
    const deform::GaussianCurvature before = deform::gaussian_curvature(V0, F);
    const deform::GaussianCurvature after = deform::gaussian_curvature(V, F);
    const double threshold =
        deform::flat_curvature_threshold(deform::curvature_reference_length(V0), options.dead_band);
    const std::vector<std::int8_t> sign_before = deform::curvature_signs(before, threshold);
    const std::vector<std::int8_t> sign_after = deform::curvature_signs(after, threshold);
    Eigen::VectorXd reversed = Eigen::VectorXd::Zero(Eigen::Index(sign_after.size()));
    for (std::size_t i = 0; i < sign_after.size(); ++i)
      if (before.defined_at(i) && sign_before[i] * sign_after[i] < 0)
        reversed(Eigen::Index(i)) = sign_after[i];
    inputs.scalars = to_render_vertices(model, reversed);
  }

  // Overlays on deform vertices.
  const Eigen::Index nv = V0.rows();
  std::vector<renderer::OverlayWeights> deform_overlays(static_cast<size_t>(nv));
  bool any_overlay = false;
  auto mark = [&](const std::vector<int>& vertices, float renderer::OverlayWeights::*field) {
    for (int v : vertices) deform_overlays[size_t(v)].*field = 1.0f;
    any_overlay = any_overlay || !vertices.empty();
  };
  auto read = [&](const std::string& file) {
    return model_file ? read_model_index_file(file, *model_file) : read_index_file(file, nv);
  };
  if (!options.roi_file.empty()) mark(read(options.roi_file), &renderer::OverlayWeights::roi);
  if (!options.fixed_file.empty()) mark(read(options.fixed_file), &renderer::OverlayWeights::fixed);
  if (!options.handle_file.empty()) mark(read(options.handle_file), &renderer::OverlayWeights::handle);
  if (!options.handle_at.empty()) {
    if (options.handle_radius <= 0.0)
      throw UsageError("--handle-at needs --handle-radius > 0 (metres at life size)");
    // The same rule as `pushpull deform`: along the surface from the closest surface point.
    deform::SurfacePoint hit;
    try {
      hit = deform::closest_surface_point(rest, vec3(options.handle_at));
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("--handle-at: ") + e.what());
    }
    // Where deform refuses such a point, the picture says it drew the handle elsewhere.
    if (const double gap = (hit.point - vec3(options.handle_at)).stableNorm(); gap > options.handle_radius)
      std::fprintf(stderr,
                   "pushpull render: warning: --handle-at is %.4g m from the surface, farther than "
                   "--handle-radius %.4g m: the handle drawn is around the nearest surface point (%s)\n",
                   gap * life_size_scale, options.handle_radius * life_size_scale,
                   point_in_metres_text(hit.point * life_size_scale).c_str());
    mark(deform::surface_handle(rest, hit, options.handle_radius), &renderer::OverlayWeights::handle);
  }
  if (any_overlay) {
    inputs.overlays.resize(model.deform_vertex.size());
    for (size_t r = 0; r < inputs.overlays.size(); ++r) {
      const int d = model.deform_vertex[r];
      if (d >= 0) inputs.overlays[r] = deform_overlays[size_t(d)];
    }
  }
  if (!options.arrow.empty()) {
    inputs.arrow = std::make_pair(vec3(options.arrow, 0), vec3(options.arrow, 3));
    if (options.sections > 0) {
      const Eigen::Vector3d d = inputs.arrow->second - inputs.arrow->first;
      if (d.norm() <= 0.0) throw UsageError("--sections needs a non-zero --arrow direction");
      const Eigen::Vector3d dn = d.normalized();
      const Eigen::VectorXd along = V * dn;
      const double lo = along.minCoeff(), hi = along.maxCoeff();
      for (int k = 1; k <= options.sections; ++k) {
        const double offset = lo + (hi - lo) * double(k) / double(options.sections + 1);
        for (const auto& curve : deform::plane_section(V, F, dn * offset, dn)) {
          std::vector<glm::vec3> line;
          for (const auto& p : curve.points) {
            const Eigen::Vector3d q = p - model.origin;  // render frame
            line.emplace_back(float(q.x()), float(q.y()), float(q.z()));
          }
          if (curve.closed && !line.empty()) line.push_back(line.front());
          inputs.sections.push_back(std::move(line));
        }
      }
    }
  } else if (options.sections > 0) {
    throw UsageError("--sections needs --arrow (the sections are orthogonal to the push/pull direction)");
  }
  return inputs;
}

}  // namespace pushpull::app
