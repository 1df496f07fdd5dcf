#include "size_steering.hpp"

#include <cmath>
#include <cstdio>

namespace pushpull::app {

void SizeSteering::frame(ReviewInteraction& interaction, float x, float y, double dt, bool enabled,
                         EventLog& log, const LifeSize& life, bool print) {
  auto factor = [&](float v) { return std::abs(v) < 0.2f ? 1.0 : std::exp2(double(v) * dt); };
  const double before = interaction.handle_radius() + interaction.roi_radius();
  if (enabled) interaction.scale_sizes(factor(y), factor(x));
  changed_ = changed_ || interaction.handle_radius() + interaction.roi_radius() != before;
  if (changed_ && std::abs(x) < 0.2f && std::abs(y) < 0.2f) {
    changed_ = false;
    log.write({{"event", "sizes"},
               {"handle_radius", interaction.handle_radius()},
               {"roi_radius", interaction.roi_radius()}});
    if (print)
      std::printf("pushpull review: handle radius %.0f mm, region %.0f mm\n",
                  life.to_mm(interaction.handle_radius()), life.to_mm(interaction.roi_radius()));
  }
}

int StickPulses::frames_per_press(double dt) {
  return int(std::lround(std::log2(kStep) / dt));
}

void StickPulses::press(int axis, int direction, double dt) {
  axis_ = axis;
  direction_ = direction;
  frames_left_ = frames_per_press(dt);
}

std::pair<float, float> StickPulses::next() {
  if (frames_left_ <= 0) return {0.0f, 0.0f};
  --frames_left_;
  const float v = float(direction_);
  return axis_ == 0 ? std::pair{v, 0.0f} : std::pair{0.0f, v};
}

}  // namespace pushpull::app
