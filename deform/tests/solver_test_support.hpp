// Shared helpers of the solver / roi / validation tests: generated sheets and the shared test meshes.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "pushpull/deform/roi.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform::solver_testing {

// (nx+1) x (ny+1) vertices on [0, width] x [0, height] in the z = 0 plane, vertex (i, j) = row j*(nx+1)+i,
// cells split along alternating diagonals.
inline Mesh sheet(int nx, int ny, double width, double height) {
  return testing::grid(nx, ny, 0.0, width, 0.0, height);
}

// A cells x cells sheet over [0, 1]^2 (z = wave sin(2 pi x) cos(1.5 pi y)), border fixed, the disk of
// `handle_radius` at the centre as handle, to be pulled by d (0.1 up).
struct PulledSheet {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  Eigen::Vector3d d{0.0, 0.0, 0.1};
};
inline PulledSheet pulled_sheet(int cells, double handle_radius, double wave) {
  Mesh m = sheet(cells, cells, 1.0, 1.0);
  std::vector<int> handle, fixed;
  for (int v = 0; v < m.V.rows(); ++v) {
    const double x = m.V(v, 0), y = m.V(v, 1);
    m.V(v, 2) = wave * std::sin(2.0 * std::numbers::pi * x) * std::cos(1.5 * std::numbers::pi * y);
    if (x < 1e-9 || y < 1e-9 || x > 1.0 - 1e-9 || y > 1.0 - 1e-9) fixed.push_back(v);
    if (std::hypot(x - 0.5, y - 0.5) <= handle_radius) handle.push_back(v);
  }
  PulledSheet s;
  s.roi = make_roi(m, handle, fixed, {});
  s.mesh = std::make_shared<const Mesh>(std::move(m));
  return s;
}

// The asan minimiser of a pulled sheet's energy, solved from rest to an estimated 1e-9 |d| (what the starts'
// tests compare against).
inline Eigen::MatrixXd asan_reference_from_rest(const PulledSheet& s) {
  DeformOptions tight;  // fresh, not a copy: GCC 12 -O2 warns on copying the empty optional
  tight.tolerance = 1e-9;
  tight.max_iterations = 50000;
  tight.smooth_start_min_free = -1;
  tight.coarse_start_min_free = -1;
  return deform(*s.mesh, s.roi, s.d, tight).V;
}

inline std::filesystem::path shared_mesh(const std::string& name) {
  return std::filesystem::path(PUSHPULL_SHARED_DATA) / "meshes" / name;
}

// The numbers of a text file, skipping '#' comment lines.
inline std::vector<double> read_numbers(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::vector<double> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double x = 0;
    while (s >> x) out.push_back(x);
  }
  return out;
}

}  // namespace pushpull::deform::solver_testing
