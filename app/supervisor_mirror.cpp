#include "supervisor_mirror.hpp"

#include "hud_clearance.hpp"

namespace pushpull::app {

SupervisorMirror::SupervisorMirror(const renderer::Context& context, renderer::Renderer& renderer,
                                   uint32_t width, uint32_t height, const renderer::Bounds& orbit_bounds)
    : renderer_(renderer),
      window_(context, width, height, "pushpull review"),
      hud_(renderer, 0.02f, 1000),
      last_pass_(std::chrono::steady_clock::now()) {
  view_.set_orbit_bounds(orbit_bounds);
}

std::vector<int> SupervisorMirror::poll() {
  window_.poll_events();
  std::vector<int> keys = window_.take_key_presses();
  if (window_.lost()) return keys;  // its pointer would be garbage; should_close() ends the loop
  view_.pointer(window_.pointer());
  return keys;
}

std::optional<renderer::RenderPass> SupervisorMirror::pass(
    const std::optional<std::array<xr::EyeView, 2>>& last_eyes,
    const std::vector<renderer::Draw>& scene_draws, const std::vector<std::string>& hud_lines,
    const renderer::FrameSettings& settings, const renderer::RenderTargets* eye_targets, bool eyes_allow_copy,
    const WorldLabel* hand_label) {
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - last_pass_).count();
  last_pass_ = now;
  target_.reset();
  if (!last_eyes) return std::nullopt;
  // Inside the headset's frame: a window image that is not free now skips this mirror frame (a blocking
  // acquire would order the runtime's work on the queue behind the window and cost headset frames).
  target_ = window_.acquire(/*timeout_ns=*/0);
  if (!target_) return std::nullopt;
  const VkExtent2D e = target_->targets.extent;
  camera_ = view_.update(*last_eyes, dt, float(e.width) / float(e.height));
  // Headset-eye mode shows the left eye as drawn (a copy, no second drawing of the scene) with the HUD and
  // the colour-map legend over it; the other modes draw their own view, with the legend and the HUD.
  const bool copy = eye_targets != nullptr && view_.mode() == MirrorMode::HeadsetEye &&
                    window_.accepts_blit() && eyes_allow_copy &&
                    renderer_.can_blit(eye_targets->format, target_->targets.format);
  if (copy)
    draws_.clear();
  else
    draws_ = scene_draws;
  hud_.set_text(hud_lines);
  hud_.place_top_left(camera_, 0.03);
  if (!copy && hand_label != nullptr)
    if (auto d = hand_label->draw()) {
      // Turned to face this view's eye (it faces the headset, which this view is not), at least as tall a
      // line as the HUD's small print, kept inside the image, then moved clear of the HUD.
      const float w = hand_label->width(), h = hand_label->height();
      d->T_world_mesh = facing_view(d->T_world_mesh, camera_);
      d->T_world_mesh =
          at_least_lines_tall(d->T_world_mesh, w, h, int(hand_label->lines().size()), camera_, 0.02f);
      d->T_world_mesh = inside_image(d->T_world_mesh, w, h, camera_, 0.02f);
      if (const auto hud = label_image_rect(hud_.transform(), hud_.width(), hud_.height(), camera_))
        d->T_world_mesh =
            clear_of_hud(d->T_world_mesh, hand_label->width(), hand_label->height(), *hud, camera_);
      draws_.push_back(*d);
    }
  if (const auto d = hud_.draw()) draws_.push_back(*d);
  renderer::RenderPass pass{std::span(&camera_, 1), draws_, settings, &target_->targets, target_->sync};
  if (view_.mode() == MirrorMode::HeadsetEye && eye_targets != nullptr) last_copied_ = copy;
  if (copy) {
    pass.blit_from = &eye_targets->views[0];
    pass.blit_from_extent = eye_targets->extent;
    ++copies_;
  }
  return pass;
}

std::string SupervisorMirror::mode_text() const {
  const std::string name = mirror_mode_name(view_.mode());
  return view_.mode() == MirrorMode::HeadsetEye && !last_copied_ ? name + " (drawn)" : name;
}

void SupervisorMirror::present() {
  if (!target_) return;
  window_.present(*target_);
  target_.reset();
  ++frames_;
}

void SupervisorMirror::abandon() {
  if (target_) window_.abandon(*target_);
  target_.reset();
}

void SupervisorMirror::set_title(const std::string& title) {
  if (title_ != title) window_.set_title(title_ = title);
}

std::string SupervisorMirror::summary() const {
  return "mirror window presented " + std::to_string(frames_) + " frames (" + std::to_string(copies_) +
         " copied from the left eye)";
}

}  // namespace pushpull::app
