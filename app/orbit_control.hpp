// The mouse on an orbit camera (the desktop workspace, the mirror's free-orbit mode): a drag turns the camera
// around the model (0.3 degree per pixel; elevation within +-89 degrees), the wheel zooms (10% per step), and
// the model's box on the stage that the camera frames.
// Thread-safety: pure functions.
#pragma once

#include "stage_placement.hpp"

#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/mirror_window.hpp"

#include <Eigen/Core>

namespace pushpull::app {

// Applies the pointer's motion since `last` while `turning` (the button the caller turns with is held in both).
void orbit_with_pointer(renderer::OrbitCamera& orbit, const renderer::MirrorWindow::Pointer& now,
                        const renderer::MirrorWindow::Pointer& last, bool turning);

// The axis-aligned box of the model's vertices (model space, #V by 3) placed on the stage.
[[nodiscard]] renderer::Bounds stage_bounds(const Eigen::MatrixXd& V, const StagePlacement& placement);

}  // namespace pushpull::app
