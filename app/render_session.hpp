// The Vulkan side of `pushpull render`: options, the prepared per-vertex inputs, and the function
// that renders them to a PNG (and optionally benchmarks frames and streaming uploads).
// Thread-safety: call from one thread (the renderer asserts it).
#pragma once

#include "pushpull/deform/metrics.hpp"
#include "life_size.hpp"
#include "render_model.hpp"

#include <Eigen/Core>
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

// Lengths and points (eye, target, handle_at, handle_radius, arrow, scalar_max, ipd) are typed in
// life-size metres (life_size.hpp); run_render converts them to file units before render_to_png.
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
  double fov_deg = 30.0;
  std::optional<double> scalar_max;
  double dead_band = deform::kDefaultFlatBand;  // curvature sign: |K| L^2 <= this is flat
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

// Everything on render vertices (#Vr), model frame.
struct RenderInputs {
  RenderModel render;
  std::vector<float> positions;                                      // #Vr*3, deformed when `deformed`
  std::vector<float> normals;                                        // #Vr*3
  std::vector<float> scalars;                                        // #Vr or empty
  double scalar_max = 0.0;                                           // largest displacement (model units)
  std::vector<renderer::OverlayWeights> overlays;                    // #Vr or empty
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> arrow;  // p0, p1
  std::vector<std::vector<glm::vec3>> sections;
  bool deformed = false;
  double life_size_scale = 1.0;  // metres per model unit: legends in life-size mm
};

// Renders and writes options.out; throws CommandError naming the file on failure.
void render_to_png(const RenderInputs& inputs, const RenderCommandOptions& options);

}  // namespace pushpull::app
