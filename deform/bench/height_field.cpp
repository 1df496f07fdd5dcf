#include "height_field.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "pushpull/deform/deformer.hpp"

namespace pushpull::bench {

HeightFieldProblem make_height_field(int n, double handle_radius, const Eigen::Vector3d& d) {
  HeightFieldProblem problem;
  problem.d = d;
  std::mt19937 rng(12345);
  const double cell = 1.0 / (n - 1);
  std::uniform_real_distribution<double> jitter(-0.25 * cell, 0.25 * cell);
  deform::Mesh& mesh = problem.mesh;
  mesh.V.resize(n * n, 3);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const bool border = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const double x = i * cell + (border ? 0.0 : jitter(rng));
      const double y = j * cell + (border ? 0.0 : jitter(rng));
      const double z = 0.05 * std::sin(2.0 * std::numbers::pi * x) * std::cos(1.5 * std::numbers::pi * y);
      const int v = j * n + i;
      mesh.V.row(v) << x, y, z;
      if (border) problem.fixed.push_back(v);
      if (std::hypot(x - 0.5, y - 0.5) <= handle_radius) problem.handle.push_back(v);
    }
  }
  mesh.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, e = c + 1;
      mesh.F.row(f++) << a, b, e;
      mesh.F.row(f++) << a, e, c;
    }
  }
  return problem;
}

Eigen::MatrixXd reference_solution(const deform::Mesh& mesh, const deform::RegionOfInterest& roi,
                                   const Eigen::Vector3d& d, deform::Method method) {
  deform::DeformOptions options;
  options.method = method;
  options.tolerance = 1e-9;
  options.max_iterations = 50000;
  return deform::deform(mesh, roi, d, options).V;
}

}  // namespace pushpull::bench
