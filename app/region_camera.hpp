// Where the replay report's pictures of one push/pull look from: at its region of interest, not the whole
// model (a 50 mm handle on a 4 m car was a few pixels of colour in a grey car).
// Frames: model frame, file units (as RenderCommandOptions::eye and ::target). Thread-safety: pure function.
#pragma once

#include "pushpull/deform/mesh.hpp"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace pushpull::app {

struct RegionCamera {
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
};

// The region's vertices (rows of before.V and after, #V by 3) boxed before and after; the camera looks at the
// box's centre along the surface normal at vertex `grabbed` (area-weighted over its faces, turned to point
// away from the model's centre), tilted away from `up` when that normal is near it (a bonnet seen from above
// and in front, not straight down, where `up` could not orient the picture), from far enough that the box's
// bounding sphere fills about 80% of a vertical field of view of fov_y_deg. None when the region is empty or
// `grabbed` is out of range.
[[nodiscard]] std::optional<RegionCamera> region_camera(const deform::Mesh& before,
                                                        const Eigen::MatrixXd& after,
                                                        const std::vector<int>& region, int grabbed,
                                                        const Eigen::Vector3d& up, double fov_y_deg);

}  // namespace pushpull::app
