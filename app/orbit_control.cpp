#include "orbit_control.hpp"

#include <algorithm>
#include <cmath>

namespace pushpull::app {

void orbit_with_pointer(renderer::OrbitCamera& orbit, const renderer::MirrorWindow::Pointer& now,
                        const renderer::MirrorWindow::Pointer& last, bool turning) {
  if (turning) {
    orbit.azimuth_deg -= float(now.x - last.x) * 0.3f;
    orbit.elevation_deg = std::clamp(orbit.elevation_deg + float(now.y - last.y) * 0.3f, -89.0f, 89.0f);
  }
  orbit.distance_scale = std::clamp(orbit.distance_scale * float(std::pow(0.9, now.scroll)), 0.05f, 10.0f);
}

renderer::Bounds stage_bounds(const Eigen::MatrixXd& V, const StagePlacement& placement) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d p = placement.to_stage_point(V.row(i).transpose());
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  renderer::Bounds bounds;
  if (V.rows() == 0) return bounds;
  bounds.min = glm::vec3(float(lo.x()), float(lo.y()), float(lo.z()));
  bounds.max = glm::vec3(float(hi.x()), float(hi.y()), float(hi.z()));
  return bounds;
}

}  // namespace pushpull::app
