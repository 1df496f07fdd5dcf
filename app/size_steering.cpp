#include "size_steering.hpp"

#include <cmath>
#include <cstdint>
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
    report_sizes(interaction, log, life, print);
  }
}

void report_sizes(const ReviewInteraction& interaction, EventLog& log, const LifeSize& life, bool print) {
  log.write({{"event", "sizes"},
             {"handle_radius", interaction.handle_radius()},
             {"roi_radius", interaction.roi_radius()}});
  if (print)
    std::printf("pushpull review: handle radius %.0f mm, region %.0f mm\n",
                life.to_mm(interaction.handle_radius()), life.to_mm(interaction.roi_radius()));
}

std::optional<SizeFactors> trackpad_click_step(float x, float y) {
  if (x * x + y * y < 0.25f) return std::nullopt;
  SizeFactors f;
  if (std::abs(y) >= std::abs(x))
    f.handle = y > 0.0f ? kSizeStep : 1.0 / kSizeStep;
  else
    f.region = x > 0.0f ? kSizeStep : 1.0 / kSizeStep;
  return f;
}

double recording_frame_period_s(double rate_hz) {
  return double(std::int64_t(1e9 / rate_hz)) * 1e-9;
}

}  // namespace pushpull::app
