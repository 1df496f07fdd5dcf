// What the review draws: the model (materials, textures, one streamed mesh) placed on the stage by
// T_stage_model, recoloured from the newest deform::Snapshot (positions, normals, displacement or
// curvature-sign scalars; while a drag's previews show, its handle red, fixed border blue and region
// tinted), and the eye views of an XR frame.
//
// Frames: the mesh is in the render frame (model space, file units, less RenderModel::origin); draws place
// it with T_stage_model * translate(origin), composed in double; views come from
// T_stage_eye poses (stage metres). Shapes: snapshot positions are #Vd by 3 (the welded deform mesh);
// the render mesh has #Vr vertices mapped by RenderModel::deform_vertex.
// Ownership: borrows the Renderer (outlives this). Thread-safety: the renderer's thread only.
#pragma once

#include "newest_only_worker.hpp"
#include "render_model.hpp"
#include "review_colour.hpp"
#include "stage_placement.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/service.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/xr/session.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace pushpull::app {

// A snapshot turned into the render mesh's vertex data for one colour map (positions, normals, scalars):
// in the vectors, or (the async scene, where the renderer has a VertexStream) in `set`, a vertex set of the
// stream written on the converter's thread, the vectors then empty.
struct SnapshotVertices {
  std::shared_ptr<const deform::Snapshot> snapshot;
  ReviewColour colour = ReviewColour::Displacement;
  std::vector<float> positions, normals, scalars;
  renderer::VertexStream::Lease set;
  double scalar_max = 0.0;  // displacement: the colour map's top (model units)
  double cpu_ms = 0.0;      // time the conversion took, on whichever thread ran it
};

// The conversion itself (pure; any thread): positions, normals and the colour map's scalars of the render
// mesh for `snapshot`; displacement is measured from rest_V (model units), its map's top rounded up to a
// round mm.
[[nodiscard]] SnapshotVertices convert_snapshot(const RenderModel& render, const Eigen::MatrixXd& rest_V,
                                                const Eigen::MatrixXi& F, double scale, ReviewColour colour,
                                                const std::shared_ptr<const deform::Snapshot>& snapshot);

class ReviewScene {
 public:
  // life_size_scale: metres per model unit (displacement legend in mm). async: snapshots are turned into
  // vertex data on a thread of the scene's own (NewestOnlyWorker), drawn one or more frames later; where the
  // renderer has a VertexStream for the mesh, that thread writes them into a vertex set the frame loop only
  // publishes (no per-frame copy of vertex data on the frame's thread), else the frame loop copies them
  // (Renderer::update_vertices).
  // converter_cpus: the CPUs the async converter's thread runs on (deform/cpu_affinity.hpp; empty: where the
  // caller's threads may).
  ReviewScene(renderer::Renderer& renderer, const assets::Model& model, const StagePlacement& placement,
              ReviewColour colour, double life_size_scale, bool async = false,
              std::vector<int> converter_cpus = {});

  // Shows the snapshot when its generation is new. Synchronous (not async, or wait): converts and uploads on
  // the calling thread, O(#Vr). Async: posts it to the converter and uploads the newest finished conversion,
  // if any.
  void update(const std::shared_ptr<const deform::Snapshot>& snapshot, bool wait = false);
  void set_colour(ReviewColour colour);
  // Model (deform) vertices to highlight as the handle a press would grab (aiming, between drags); empty:
  // none. Ignored while a drag's previews show their own overlays. Uploads overlays only when the set
  // changes.
  void set_highlight(const std::vector<int>& vertices);
  void set_placement(const StagePlacement& placement);
  [[nodiscard]] ReviewColour colour() const { return colour_; }
  [[nodiscard]] std::uint64_t generation() const { return generation_; }  // of the snapshot drawn
  // CPU time of the last snapshot's conversion to vertex data (before the upload, which may wait for the GPU
  // to release its staging slot).
  [[nodiscard]] double last_cpu_ms() const { return last_cpu_ms_; }

  [[nodiscard]] std::vector<renderer::Draw> draws() const;
  // legend: draw the colour map's legend (windows); the headset's eyes go without.
  [[nodiscard]] renderer::FrameSettings settings(bool legend = false) const;
  // The window the legend is drawn in (pixels): sizes the legend's texture and rectangle. The legend is made
  // only once a window has asked for it (a headset without a mirror window never draws one).
  void set_legend_window(uint32_t width, uint32_t height);

 private:
  void upload();                          // converts last_ on this thread and applies it
  void apply(SnapshotVertices vertices);  // overlays, upload, legend
  void update_legend();  // the renderer's legend for the colour map and its top (only when they change)

  renderer::Renderer& renderer_;
  RenderModel render_;
  Eigen::MatrixXd rest_V_;  // the model as loaded: displacement is measured from it
  Eigen::MatrixXi F_;
  renderer::MeshId mesh_ = 0;
  glm::mat4 T_stage_render_{1.0f};
  ReviewColour colour_;
  double scale_ = 1.0;
  double scalar_max_ = 0.0;
  std::uint64_t generation_ = 0;
  std::shared_ptr<const deform::RegionOfInterest> shown_region_;  // whose roles the overlays show
  bool overlays_shown_ = false;
  std::vector<int> highlight_;    // the handle-to-be under the aim
  bool highlight_shown_ = false;  // its overlays are in the mesh
  size_t vertex_count_ = 0;       // #Vr
  bool drawn_ = false;            // a snapshot's vertex data has been given to the renderer
  // The renderer's zero-copy stream for the mesh (async scenes only; null: update_vertices copies). Written
  // into by the converter's thread.
  std::shared_ptr<renderer::VertexStream> stream_;
  double last_cpu_ms_ = 0.0;
  uint32_t legend_width_ = 960, legend_height_ = 540;
  bool legend_wanted_ = false;  // a window has asked for the legend (set_legend_window)
  std::optional<std::pair<ReviewColour, double>> legend_shown_;  // colour map and top (mm) of the legend
  std::shared_ptr<const deform::Snapshot> last_;
  std::uint64_t latest_generation_ = 0;  // of the newest snapshot given to update()
  struct ConversionJob {
    std::shared_ptr<const deform::Snapshot> snapshot;
    ReviewColour colour;
  };
  // Last: its thread reads render_, rest_V_, F_, scale_ and stream_ (never changed after construction) and
  // must stop before they go (its results' leases of stream_ too: before the renderer goes).
  std::unique_ptr<NewestOnlyWorker<ConversionJob, SnapshotVertices>> converter_;
};

// Image views for the eye swapchains' images and the RenderTargets of one frame.
// Ownership: owns the views; borrows the images (the swapchains outlive this).
class EyeTargets {
 public:
  EyeTargets(VkDevice device, xr::Swapchain& left, xr::Swapchain& right);
  ~EyeTargets();
  EyeTargets(const EyeTargets&) = delete;
  EyeTargets& operator=(const EyeTargets&) = delete;

  // Targets for the images acquired at these indices (left, right).
  [[nodiscard]] renderer::RenderTargets targets(uint32_t left_index, uint32_t right_index) const;

 private:
  VkDevice device_;
  std::array<xr::Swapchain*, 2> swapchains_;
  std::array<std::vector<VkImageView>, 2> views_;
};

// The renderer's view of an eye: T_eye_stage and the asymmetric projection of its field of view.
renderer::View eye_view(const xr::EyeView& eye, float z_near = 0.05f, float z_far = 100.0f);

}  // namespace pushpull::app
