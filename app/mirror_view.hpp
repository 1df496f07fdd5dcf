// The supervisor's view in the mirror window, from the headset's eye poses.
//
// Modes: HeadsetEye (the left eye's pose, the eye's vertical field of view at the window's aspect),
// SmoothedFirstPerson (the head between the eyes with roll removed, position and heading low-passed with a
// 0.5 s time constant, pitch followed as is: what the reviewer looks at without the headset's jitter) and
// FreeOrbit (the supervisor's own camera around the model: drag with either mouse button to turn, wheel to zoom;
// it starts looking from where the reviewer stands).
// Frames: eye poses T_stage_eye (stage metres); the View maps stage to the mirror camera.
// Thread-safety: one instance, the frame loop's thread.
#pragma once

#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/mirror_window.hpp"
#include "pushpull/renderer/types.hpp"
#include "pushpull/xr/session.hpp"

#include <glm/glm.hpp>

#include <optional>

namespace pushpull::app {

enum class MirrorMode { HeadsetEye, SmoothedFirstPerson, FreeOrbit };
// Headset eye -> smoothed first person -> free orbit -> headset eye.
[[nodiscard]] MirrorMode next_mirror_mode(MirrorMode mode);
const char* mirror_mode_name(MirrorMode mode);

class MirrorView {
 public:
  // eyes: this frame's eye views; dt_s: time since the last call; aspect: window width / height.
  renderer::View update(const std::array<xr::EyeView, 2>& eyes, double dt_s, float aspect);
  void set_mode(MirrorMode mode);
  // FreeOrbit: the model's box on the stage (what the orbit frames) and the window's pointer each frame.
  void set_orbit_bounds(const renderer::Bounds& bounds) { bounds_ = bounds; }
  void pointer(const renderer::MirrorWindow::Pointer& p);
  [[nodiscard]] MirrorMode mode() const { return mode_; }

 private:
  MirrorMode mode_ = MirrorMode::HeadsetEye;
  std::optional<glm::dvec3> position_;  // smoothed head position, stage
  double yaw_ = 0.0;                    // smoothed heading, radians about stage +Y
  renderer::OrbitCamera orbit_;
  renderer::Bounds bounds_;
  std::optional<renderer::MirrorWindow::Pointer> last_pointer_;
  double head_yaw_ = 0.0;  // the reviewer's latest heading (FreeOrbit starts behind it)
};

}  // namespace pushpull::app
