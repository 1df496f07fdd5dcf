#include "review_scene.hpp"

#include "pushpull/deform/cpu_affinity.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/geometry.hpp"
#include "pushpull/renderer/vk_check.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace pushpull::app {
namespace {

// The smallest of 1, 2, 2.5, 5 times a power of ten that is >= mm (> 0).
double round_up_mm(double mm) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(mm)));
  for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * magnitude >= mm * (1.0 - 1e-12)) return m * magnitude;
  return 10.0 * magnitude;
}

}  // namespace

ReviewScene::ReviewScene(renderer::Renderer& renderer, const assets::Model& model,
                         const StagePlacement& placement, ReviewColour colour, double life_size_scale,
                         bool async, std::vector<int> converter_cpus)
    : renderer_(renderer),
      render_(build_render_model(model)),
      rest_V_(model.deform_mesh.V),
      F_(model.deform_mesh.F),
      colour_(colour),
      scale_(life_size_scale) {
  if (render_.mesh.indices.empty()) throw std::invalid_argument("the model has no triangles to draw");
  std::vector<renderer::TextureId> texture_ids;
  for (const auto& t : render_.textures) texture_ids.push_back(renderer_.add_texture(t));
  auto tex = [&](int i) { return i >= 0 ? int(texture_ids[size_t(i)]) : -1; };
  std::vector<int> material_ids;
  for (renderer::Material m : render_.materials) {
    m.base_colour_texture = tex(m.base_colour_texture);
    m.metallic_roughness_texture = tex(m.metallic_roughness_texture);
    m.normal_texture = tex(m.normal_texture);
    m.occlusion_texture = tex(m.occlusion_texture);
    m.emissive_texture = tex(m.emissive_texture);
    material_ids.push_back(int(renderer_.add_material(m)));
  }
  renderer::RenderMesh mesh = render_.mesh;
  mesh.positions = render_positions(render_, rest_V_);
  mesh.normals = render_.file_normals;
  mesh.scalars.assign(mesh.vertex_count(), 0.0f);
  for (auto& sub : mesh.submeshes) sub.material = sub.material >= 0 ? material_ids[size_t(sub.material)] : -1;
  vertex_count_ = mesh.vertex_count();
  mesh_ = renderer_.add_mesh(mesh, /*streamed=*/true);
  set_placement(placement);
  if (async) {
    stream_ = renderer_.vertex_stream(mesh_);
    converter_ = std::make_unique<NewestOnlyWorker<ConversionJob, SnapshotVertices>>(
        [this](const ConversionJob& job) {
          SnapshotVertices out = convert_snapshot(render_, rest_V_, F_, scale_, job.colour, job.snapshot);
          if (!stream_) return out;
          // Into a vertex set the frame loop binds as it is (none free: the frame loop copies the vectors).
          const auto start = std::chrono::steady_clock::now();
          renderer::VertexStream::Lease set = stream_->acquire();
          if (!set) return out;
          std::copy(out.positions.begin(), out.positions.end(), set.positions().begin());
          std::copy(out.normals.begin(), out.normals.end(), set.normals().begin());
          std::copy(out.scalars.begin(), out.scalars.end(), set.scalars().begin());
          out.set = std::move(set);
          out.positions = {};  // freed here, not on the frame's thread
          out.normals = {};
          out.scalars = {};
          out.cpu_ms +=
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
          return out;
        },
        [cpus = std::move(converter_cpus)] { (void)deform::pin_calling_thread(cpus); });
  }
}

void ReviewScene::set_placement(const StagePlacement& placement) {
  // The mesh is in the render frame (render_model.hpp): stage <- model <- render, composed in double.
  Eigen::Matrix4d T_stage_render = placement.T_stage_model;
  T_stage_render.topRightCorner<3, 1>() += placement.T_stage_model.topLeftCorner<3, 3>() * render_.origin;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T_stage_render_[c][r] = float(T_stage_render(r, c));
}

void ReviewScene::set_colour(ReviewColour colour) {
  if (colour == colour_) return;
  colour_ = colour;
  if (last_)
    upload();  // at once, on this thread (a conversion in flight for the old map is dropped); sets the legend
  else
    update_legend();
}

void ReviewScene::update(const std::shared_ptr<const deform::Snapshot>& snapshot, bool wait) {
  const bool is_new = snapshot->generation != latest_generation_;
  latest_generation_ = snapshot->generation;
  last_ = snapshot;
  if (!converter_ || wait) {
    // On this thread: the frame shows exactly this snapshot (replays: the same images on every run).
    if (generation_ != snapshot->generation) upload();
    return;
  }
  if (is_new) converter_->post({snapshot, colour_});
  // The newest finished conversion, when it is still of the colour map shown and newer than what is drawn.
  if (auto v = converter_->take(); v && v->colour == colour_ && v->snapshot->generation > generation_)
    apply(std::move(*v));
}

SnapshotVertices convert_snapshot(const RenderModel& render, const Eigen::MatrixXd& rest_V,
                                  const Eigen::MatrixXi& F, double scale, ReviewColour colour,
                                  const std::shared_ptr<const deform::Snapshot>& snapshot) {
  const auto start = std::chrono::steady_clock::now();
  SnapshotVertices out;
  out.snapshot = snapshot;
  out.colour = colour;
  const Eigen::MatrixXd& V = *snapshot->positions;
  out.positions = render_positions(render, V);
  out.normals = deformed_normals(render, out.positions);
  if (colour == ReviewColour::Displacement) {
    const Eigen::VectorXd magnitude = (V - rest_V).rowwise().norm();
    out.scalars = to_render_vertices(render, magnitude);
    // The colour map's top: the largest displacement, at least 1 mm at life size, rounded up to a round
    // number of mm (1, 2, 2.5 or 5 times a power of ten), so the legend's scale changes only now and then in
    // a drag.
    const double largest_mm = 1000.0 * scale * (magnitude.size() ? magnitude.maxCoeff() : 0.0);
    out.scalar_max = round_up_mm(std::max(largest_mm, 1.0)) / (1000.0 * scale);
  } else if (colour == ReviewColour::CurvatureSign) {
    const deform::GaussianCurvature K = deform::gaussian_curvature(V, F);
    const double threshold = deform::flat_curvature_threshold(deform::curvature_reference_length(rest_V),
                                                              deform::kDefaultFlatBand);
    std::vector<std::int8_t> signs = deform::curvature_signs(K, threshold);
    for (size_t i = 0; i < signs.size(); ++i)
      if (!K.defined_at(i)) signs[i] = 0;
    out.scalars = curvature_signs_on_render_vertices(render, V, signs);
  } else {
    out.scalars.assign(out.positions.size() / 3, 0.0f);
  }
  out.cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void ReviewScene::upload() {
  apply(convert_snapshot(render_, rest_V_, F_, scale_, colour_, last_));
}

void ReviewScene::apply(SnapshotVertices v) {
  const deform::Snapshot& snapshot = *v.snapshot;
  generation_ = snapshot.generation;
  if (colour_ == ReviewColour::Displacement) scalar_max_ = v.scalar_max;
  // The drag's region while its previews show; nothing once committed, cancelled or undone.
  const bool show = snapshot.kind == deform::Snapshot::Kind::Preview && snapshot.region != nullptr;
  std::vector<renderer::OverlayWeights> overlays;
  if (show ? snapshot.region != shown_region_ : (overlays_shown_ || highlight_shown_)) {
    overlays.assign(vertex_count_, renderer::OverlayWeights{});
    if (show) {
      const auto& role = snapshot.region->role;
      for (size_t r = 0; r < overlays.size(); ++r) {
        const int d = render_.deform_vertex[r];
        if (d < 0) continue;
        const deform::VertexRole vr = role[size_t(d)];
        overlays[r].roi = vr != deform::VertexRole::Outside ? 1.0f : 0.0f;
        overlays[r].handle = vr == deform::VertexRole::Handle ? 1.0f : 0.0f;
        overlays[r].fixed = vr == deform::VertexRole::Fixed ? 1.0f : 0.0f;
      }
    }
    shown_region_ = show ? snapshot.region : nullptr;
    overlays_shown_ = show;
    highlight_shown_ = false;
    highlight_.clear();
  }
  last_cpu_ms_ = v.cpu_ms;
  if (v.set) {  // written by the converter: no copy here
    if (!overlays.empty()) renderer_.update_vertices(mesh_, {}, {}, {}, overlays);
    stream_->publish(std::move(v.set));
  } else {
    renderer_.update_vertices(mesh_, v.positions, v.normals, v.scalars, overlays);
  }
  drawn_ = true;
  update_legend();
}

void ReviewScene::set_legend_window(uint32_t width, uint32_t height) {
  if (!legend_wanted_) {  // the first window that shows the legend: make it now
    legend_wanted_ = true;
    legend_shown_.reset();
  }
  if (width == legend_width_ && height == legend_height_) {
    update_legend();
    return;
  }
  legend_width_ = std::max(width, 1u);
  legend_height_ = std::max(height, 1u);
  legend_shown_.reset();
  update_legend();
}

void ReviewScene::update_legend() {
  if (!legend_wanted_) return;  // the headset's eyes go without: no texture to make or upload
  const double top_mm = 1000.0 * scale_ * std::max(scalar_max_, 1e-3 / scale_);
  const std::pair<ReviewColour, double> wanted{colour_, colour_ == ReviewColour::Displacement ? top_mm : 0.0};
  if (legend_shown_ == wanted) return;
  legend_shown_ = wanted;
  // Lower-left corner, about a third of the window high (as `pushpull render` places it).
  const renderer::LegendLayout legend = renderer::legend_layout(legend_width_, legend_height_);
  if (colour_ == ReviewColour::Displacement) {
    renderer_.set_legend(
        renderer::make_displacement_legend(float(top_mm), "moved mm", legend.width_px, legend.height_px),
        legend.rect);
  } else if (colour_ == ReviewColour::CurvatureSign) {
    renderer_.set_legend(renderer::make_curvature_legend(legend.curvature_width_px, legend.height_px / 2),
                         legend.curvature_rect);
  } else {
    renderer_.set_legend(std::nullopt);
  }
}

void ReviewScene::set_highlight(const std::vector<int>& vertices) {
  // The drag's own overlays (region, handle, fixed border) win while its previews show.
  if (overlays_shown_ || !drawn_) return;
  if (vertices == highlight_ && highlight_shown_ == !vertices.empty()) return;
  highlight_ = vertices;
  std::vector<char> mark(size_t(rest_V_.rows()), 0);
  for (int v : vertices)
    if (v >= 0 && v < int(mark.size())) mark[size_t(v)] = 1;
  std::vector<renderer::OverlayWeights> overlays(vertex_count_, renderer::OverlayWeights{});
  for (size_t r = 0; r < overlays.size(); ++r) {
    const int d = render_.deform_vertex[r];
    if (d >= 0 && mark[size_t(d)]) overlays[r].handle = overlays[r].fixed = 1.0f;  // the hover colour
  }
  renderer_.update_vertices(mesh_, {}, {}, {}, overlays);  // the overlays alone (positions as they are)
  highlight_shown_ = !vertices.empty();
}

std::vector<renderer::Draw> ReviewScene::draws() const {
  return {renderer::Draw{mesh_, T_stage_render_}};
}

renderer::FrameSettings ReviewScene::settings(bool legend) const {
  renderer::FrameSettings s;
  s.show_legend = legend;
  s.up = {0.0f, 1.0f, 0.0f};  // stage
  switch (colour_) {
    case ReviewColour::Material:
      s.color_mode = renderer::ColorMode::material;
      break;
    case ReviewColour::Displacement:
      s.color_mode = renderer::ColorMode::displacement;
      s.scalar_max = float(std::max(scalar_max_, 1e-3 / scale_));
      break;
    case ReviewColour::CurvatureSign:
      s.color_mode = renderer::ColorMode::curvature_sign;
      s.curvature_epsilon = 0.5f;  // scalars are the signs -1 / 0 / +1
      break;
  }
  return s;
}

EyeTargets::EyeTargets(VkDevice device, xr::Swapchain& left, xr::Swapchain& right)
    : device_(device), swapchains_{&left, &right} {
  if (left.width() != right.width() || left.height() != right.height() || left.format() != right.format())
    throw std::runtime_error(
        "the eye swapchains differ in size or format; the renderer draws both eyes at one size");
  for (size_t e = 0; e < 2; ++e)
    for (VkImage image : swapchains_[e]->images()) {
      VkImageViewCreateInfo info{};
      info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
      info.image = image;
      info.viewType = VK_IMAGE_VIEW_TYPE_2D;
      info.format = swapchains_[e]->format();
      info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      VkImageView view = VK_NULL_HANDLE;
      PP_VK_CHECK(vkCreateImageView(device_, &info, nullptr, &view));
      views_[e].push_back(view);
    }
}

EyeTargets::~EyeTargets() {
  for (auto& eye : views_)
    for (VkImageView v : eye) vkDestroyImageView(device_, v, nullptr);
}

renderer::RenderTargets EyeTargets::targets(uint32_t left_index, uint32_t right_index) const {
  renderer::RenderTargets t;
  t.extent = {swapchains_[0]->width(), swapchains_[0]->height()};
  t.format = swapchains_[0]->format();
  const uint32_t index[2] = {left_index, right_index};
  for (size_t e = 0; e < 2; ++e) {
    renderer::ColorTarget c;
    c.image = swapchains_[e]->images().at(index[e]);
    c.view = views_[e].at(index[e]);
    c.initial_layout = VK_IMAGE_LAYOUT_UNDEFINED;               // cleared anyway
    c.final_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // what XR_KHR_vulkan_enable2 expects back
    t.views.push_back(c);
  }
  return t;
}

renderer::View eye_view(const xr::EyeView& eye, float z_near, float z_far) {
  const XrQuaternionf& q = eye.T_stage_eye.orientation;
  const XrVector3f& p = eye.T_stage_eye.position;
  glm::mat4 T_stage_eye = glm::mat4_cast(glm::quat(q.w, q.x, q.y, q.z));
  T_stage_eye[3] = glm::vec4(p.x, p.y, p.z, 1.0f);
  renderer::View view;
  view.view = glm::inverse(T_stage_eye);
  view.projection = renderer::projection_from_fov(eye.fov.angleLeft, eye.fov.angleRight, eye.fov.angleUp,
                                                  eye.fov.angleDown, z_near, z_far);
  return view;
}

}  // namespace pushpull::app
