// The only translation unit that includes CGAL (heavy to compile).
#include "cgal_peer.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

#include <chrono>

namespace pushpull::bench {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using Deformation =
    CGAL::Surface_mesh_deformation<SurfaceMesh, CGAL::Default, CGAL::Default, CGAL::SPOKES_AND_RIMS>;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}
}  // namespace

PeerRun run_cgal_spokes_and_rims(const deform::Mesh& mesh, const std::vector<int>& handle,
                                 const std::vector<int>& fixed, const Eigen::Vector3d& d,
                                 const Eigen::MatrixXd& reference, double target_error, int max_iterations) {
  SurfaceMesh sm;
  std::vector<VertexIndex> vertex(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    vertex[static_cast<std::size_t>(i)] =
        sm.add_vertex(Kernel::Point_3(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)));
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    sm.add_face(vertex[static_cast<std::size_t>(mesh.F(f, 0))],
                vertex[static_cast<std::size_t>(mesh.F(f, 1))],
                vertex[static_cast<std::size_t>(mesh.F(f, 2))]);
  }
  std::vector<bool> is_fixed(vertex.size(), false);
  for (const int v : fixed) is_fixed[static_cast<std::size_t>(v)] = true;

  PeerRun run;
  const auto start = Clock::now();
  Deformation deformation(sm);
  for (std::size_t i = 0; i < vertex.size(); ++i) {
    if (!is_fixed[i]) deformation.insert_roi_vertex(vertex[i]);
  }
  for (const int v : handle) deformation.insert_control_vertex(vertex[static_cast<std::size_t>(v)]);
  deformation.preprocess();
  run.preprocess_ms = ms_since(start);
  const Kernel::Vector_3 t(d.x(), d.y(), d.z());
  for (const int v : handle) deformation.translate(vertex[static_cast<std::size_t>(v)], t);

  Eigen::MatrixXd current(mesh.V.rows(), 3);
  double iterate_ms = 0.0;
  for (run.iterations = 1; run.iterations <= max_iterations; ++run.iterations) {
    const auto step = Clock::now();
    deformation.deform(1, 0.0);
    iterate_ms += ms_since(step);
    for (std::size_t i = 0; i < vertex.size(); ++i) {
      const Kernel::Point_3& p = sm.point(vertex[i]);
      current.row(static_cast<Eigen::Index>(i)) << p.x(), p.y(), p.z();
    }
    run.error = (current - reference).rowwise().norm().maxCoeff();
    if (run.error <= target_error) {
      run.converged = true;
      break;
    }
  }
  run.iterations = std::min(run.iterations, max_iterations);
  run.per_iteration_ms = iterate_ms / run.iterations;
  run.converge_ms = run.preprocess_ms + iterate_ms;
  run.V = current;
  return run;
}

}  // namespace pushpull::bench
