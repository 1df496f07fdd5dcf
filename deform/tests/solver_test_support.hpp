// Shared helpers of the solver / roi / validation tests: generated sheets and the shared test meshes.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pushpull/deform/mesh.hpp"
#include "pushpull/deform/mesh_io.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform::solver_testing {

// (nx+1) x (ny+1) vertices on [0, width] x [0, height] in the z = 0 plane, vertex (i, j) = row j*(nx+1)+i,
// cells split along alternating diagonals.
inline Mesh sheet(int nx, int ny, double width, double height) {
  return testing::grid(nx, ny, 0.0, width, 0.0, height);
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
