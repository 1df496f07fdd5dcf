// What one picture of a model draws: the options of `pushpull render` and the per-vertex inputs prepared from
// them (positions, normals, colour-map values, overlays, arrow, section curves), for the renderer
// (render_session.hpp). Used by `pushpull render` and by the replay report's pictures.
// Thread-safety: pure functions on values.
#pragma once

#include "life_size.hpp"
#include "pushpull/assets/weld.hpp"
#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/metrics.hpp"
#include "render_model.hpp"

#include <Eigen/Core>
#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

// Lengths and points (eye, target, handle_at, handle_radius, arrow, scalar_max, ipd) are typed in
// life-size metres (life_size.hpp); `pushpull render` converts them to file units before preparing.
struct RenderCommandOptions {
  std::string model;
  std::string deformed;
  std::string out;
  std::vector<int> size{1280, 960};
  std::string color = "material";
  std::vector<double> camera;  // azimuth, elevation [, zoom]
  std::vector<double> eye;
  std::vector<double> target;
  std::vector<double> up{0.0, 1.0, 0.0};
  bool up_given =
      false;  // --up was given (a plain mesh standing on its side is said otherwise: up_axis_note.hpp)
  double fov_deg = 30.0;
  std::optional<double> scalar_max;
  double dead_band = deform::kDefaultFlatBand;  // curvature sign: |K| L^2 <= this is flat
  double weld_tolerance = assets::WeldOptions{}.relative_tolerance;  // of the bounding-box diagonal
  std::string handle_file, fixed_file, roi_file;
  std::vector<double> handle_at;
  double handle_radius = 0.0;
  std::vector<double> arrow;
  int sections = 0;
  bool no_legend = false;
  bool flat = false;
  std::optional<double> ipd;
  int samples = 4;
  bool validation = false;
  int benchmark_frames = 0;
  LifeSizeOptions life_size;
};

// Everything on render vertices (#Vr). Frames: positions, sections and frame in the render frame (the model
// frame shifted by -render->origin, file units: render_model.hpp); arrow in the model frame.
struct RenderInputs {
  std::shared_ptr<const RenderModel> render;                         // shared by the pictures of one model
  std::vector<float> positions;                                      // #Vr*3, deformed when `deformed`
  std::vector<float> normals;                                        // #Vr*3
  std::vector<float> scalars;                                        // #Vr or empty
  double scalar_max = 0.0;                                           // largest displacement (model units)
  std::vector<renderer::OverlayWeights> overlays;                    // #Vr or empty
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> arrow;  // p0, p1
  std::vector<std::vector<glm::vec3>> sections;
  bool deformed = false;
  double life_size_scale = 1.0;  // metres per model unit: legends in life-size mm
  // The box the camera frames (render frame); none: the box of `positions`. A before / after pair given the
  // box of both is drawn from one camera (a push/pull that grows the model moved the whole picture).
  std::optional<std::pair<glm::vec3, glm::vec3>> frame;  // min, max
};

// One picture's inputs: the positions V (#Vd by 3) drawn on `render` (built from the model whose deform mesh
// has the faces of `rest`); `deformed`: V differs from the positions `render` was built from (its normals are
// then turned with the surface). The colours are measured from rest.V: displacement |V - rest.V|, the
// curvature sign by deform's rule with L = rest.V's bounding-box diagonal; index files and --handle-at select
// vertices of rest (index files numbered as `pushpull deform` reads them for `model_file`, the model rest was
// welded from: read_model_index_file; without it, rest's own rows). options' lengths in file units (arrow,
// handle_at, handle_radius). Throws CommandError naming the file or option at fault.
RenderInputs prepare_render_inputs(std::shared_ptr<const RenderModel> render, const deform::Mesh& rest,
                                   const Eigen::MatrixXd& V, bool deformed,
                                   const RenderCommandOptions& options, double life_size_scale,
                                   const assets::Model* model_file = nullptr);

}  // namespace pushpull::app
