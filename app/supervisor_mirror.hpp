// The supervisor's mirror window in the headset loop (`pushpull review --mirror`): the GLFW window, its view
// mode (mirror_view.hpp), its HUD, its title and what it presented. Per loop frame: poll() for its keys, then
// pass() for its part of the frame's one submission (a copy of the left eye with the HUD over it in
// headset-eye mode, else its own view of the scene), present() once the frame is submitted, or abandon() when
// the frame threw in between.
//
// Ownership: owns the window; borrows the Context and the Renderer (they outlive it). Thread-safety: the
// frame loop's thread (GLFW's main-thread rule).
#pragma once

#include "mirror_view.hpp"
#include "world_label.hpp"

#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/mirror_window.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/xr/session.hpp"

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

class SupervisorMirror {
 public:
  // A width x height window titled "pushpull review"; the free orbit frames orbit_bounds (stage).
  SupervisorMirror(const renderer::Context& context, renderer::Renderer& renderer, uint32_t width,
                   uint32_t height, const renderer::Bounds& orbit_bounds);

  // The window's events: the keys pressed since the last poll (GLFW codes, as MirrorWindow gives them); the
  // pointer goes to the free orbit.
  std::vector<int> poll();
  [[nodiscard]] bool should_close() const { return window_.should_close(); }
  // The window was destroyed from outside (renderer::MirrorWindow::lost).
  [[nodiscard]] bool lost() const { return window_.lost(); }
  // renderer::MirrorWindow::on_connection_lost: the X display's connection broke, and the process ends.
  [[nodiscard]] renderer::MirrorWindow::LastWords on_connection_lost(std::function<void()> last_words) {
    return window_.on_connection_lost(std::move(last_words));
  }
  void set_orbit_bounds(const renderer::Bounds& bounds) { view_.set_orbit_bounds(bounds); }
  [[nodiscard]] MirrorMode mode() const { return view_.mode(); }
  // The mode's name for the HUD and the title; "headset eye (drawn)" when the last frame could not copy the
  // eye (a runtime that refuses copies) and drew the eye's view itself.
  [[nodiscard]] std::string mode_text() const;
  void next_mode() { view_.set_mode(next_mirror_mode(view_.mode())); }

  // This frame's pass into the window, or nullopt (no eye pose seen yet, or no image: minimised, resized).
  // last_eyes: the newest eye poses; scene_draws: the frame's draws (drawn in the mirror's own views);
  // hud_lines: its HUD; settings: the scene's, with the legend; eye_targets: the eyes drawn by an earlier
  // pass of this frame (null: none), copied in headset-eye mode when the formats and usages allow it;
  // hand_label: the readout by the hand (null: none), drawn in the mirror's own views moved down the image
  // where it would lie under the HUD (hud_clearance.hpp; the eyes' copy shows it where the eyes do). The
  // pass refers to members of this object, valid until the next call.
  std::optional<renderer::RenderPass> pass(const std::optional<std::array<xr::EyeView, 2>>& last_eyes,
                                           const std::vector<renderer::Draw>& scene_draws,
                                           const std::vector<std::string>& hud_lines,
                                           const renderer::FrameSettings& settings,
                                           const renderer::RenderTargets* eye_targets, bool eyes_allow_copy,
                                           const WorldLabel* hand_label = nullptr);
  // Presents the image pass() drew into, once the frame is submitted (nothing when there was none).
  void present();
  // The frame that acquired the image threw before presenting it (MirrorWindow::abandon).
  void abandon();
  // The title, set only when it changed.
  void set_title(const std::string& title);
  // "mirror window presented N frames (M copied from the left eye)".
  [[nodiscard]] std::string summary() const;

 private:
  renderer::Renderer& renderer_;
  renderer::MirrorWindow window_;
  MirrorView view_;
  WorldLabel hud_;
  std::string title_;
  std::optional<renderer::MirrorWindow::Frame> target_;  // acquired by pass(), not yet presented
  renderer::View camera_;
  std::vector<renderer::Draw> draws_;  // what the pass draws: the scene's and the HUD (a copied eye: the HUD)
  std::chrono::steady_clock::time_point last_pass_;
  std::size_t frames_ = 0, copies_ = 0;
  bool last_copied_ = true;  // the last pass in headset-eye mode copied the eye
};

}  // namespace pushpull::app
