#include "region_camera.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace pushpull::app {

std::optional<RegionCamera> region_camera(const deform::Mesh& before, const Eigen::MatrixXd& after,
                                          const std::vector<int>& region, int grabbed,
                                          const Eigen::Vector3d& up, double fov_y_deg) {
  const Eigen::Index n = before.V.rows();
  if (region.empty() || grabbed < 0 || grabbed >= n || after.rows() != n) return std::nullopt;
  Eigen::AlignedBox3d box;
  for (const int v : region) {
    if (v < 0 || v >= n) continue;
    box.extend(Eigen::Vector3d(before.V.row(v).transpose()));
    box.extend(Eigen::Vector3d(after.row(v).transpose()));
  }
  if (box.isEmpty()) return std::nullopt;
  // The surface's normal at the grabbed vertex, from its faces (their cross products: area-weighted).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (Eigen::Index f = 0; f < before.F.rows(); ++f)
    if (before.F(f, 0) == grabbed || before.F(f, 1) == grabbed || before.F(f, 2) == grabbed) {
      const Eigen::Vector3d a = before.V.row(before.F(f, 0)), b = before.V.row(before.F(f, 1)),
                            c = before.V.row(before.F(f, 2));
      normal += (b - a).cross(c - a);
    }
  const Eigen::Vector3d at = before.V.row(grabbed).transpose();
  Eigen::AlignedBox3d model;
  for (Eigen::Index v = 0; v < n; ++v) model.extend(Eigen::Vector3d(before.V.row(v).transpose()));
  const Eigen::Vector3d outward = at - model.center();
  if (!(normal.stableNorm() > 0.0)) normal = outward;  // no face at it: from the model's centre outwards
  if (!(normal.stableNorm() > 0.0)) normal = up;
  normal = normal.stableNormalized();
  if (normal.dot(outward) < 0.0) normal = -normal;  // CAD patches wound either way: seen from outside
  const Eigen::Vector3d up_unit =
      up.stableNorm() > 0.0 ? Eigen::Vector3d(up.stableNormalized()) : Eigen::Vector3d::UnitY();
  Eigen::Vector3d direction = normal;
  if (std::abs(normal.dot(up_unit)) > 0.8) {
    // Near the up axis: tilted towards the side the grabbed point lies on, seen from there.
    Eigen::Vector3d side = outward - outward.dot(up_unit) * up_unit;
    if (!(side.stableNorm() > 1e-9 * (model.diagonal().norm() + 1e-300))) side = up_unit.unitOrthogonal();
    direction = (normal + 0.8 * side.stableNormalized()).stableNormalized();
  }
  const double radius = std::max(0.5 * box.diagonal().norm(), 1e-12 * (model.diagonal().norm() + 1e-300));
  const double half_fov = 0.5 * fov_y_deg * std::numbers::pi / 180.0;
  const double distance = radius / (0.8 * std::tan(half_fov));
  RegionCamera camera;
  camera.target = box.center();
  camera.eye = camera.target + distance * direction;
  return camera;
}

}  // namespace pushpull::app
