#include "drag_notes.hpp"

#include <algorithm>
#include <cstdio>

namespace pushpull::app {

std::vector<std::string> drag_notes(double pull, double handle_radius, const deform::Snapshot& s) {
  std::vector<std::string> lines;
  char c[96];
  const double ratio = pull / std::max(handle_radius, 1e-12);
  if (ratio > kSteepPull) {
    std::snprintf(c, sizeof c, "steep: %.0fx the handle radius", ratio);
    lines.emplace_back(c);
  }
  if (s.kind != deform::Snapshot::Kind::Preview) return lines;  // not this drag's yet
  const double solved_pull = s.d.norm();  // the snapshot's own request (the hand may be ahead of it)
  if (solved_pull > 0.0 && s.max_displacement > kOvershoot * solved_pull) {
    std::snprintf(c, sizeof c, "the surface moves %.1fx the pull", s.max_displacement / solved_pull);
    lines.emplace_back(c);
  }
  if (s.region && s.region->fixed.empty())
    lines.emplace_back(s.region->whole_parts ? "the whole part moves: no border holds it"
                                             : "only the handle moves: no region beyond it");
  return lines;
}

std::optional<std::string> steep_pull_warning(double pull, double handle_radius) {
  if (!(handle_radius > 0.0) || !(pull > kSteepPull * handle_radius)) return std::nullopt;
  char text[160];
  std::snprintf(text, sizeof text,
                "steep: |d| is %.0fx the handle radius, a spike rather than a bulge (a larger handle radius "
                "spreads it)",
                pull / handle_radius);
  return std::string(text);
}

std::optional<std::string> long_pull_warning(double pull, double longest_side, double scale) {
  if (!(longest_side > 0.0) || !(pull > longest_side)) return std::nullopt;
  char text[200];
  std::snprintf(
      text, sizeof text,
      "a pull of %.2f m, %.1f times the model's longest side (%.2f m): a tracking jump at the release?; "
      "undo takes it back",
      scale * pull, pull / longest_side, scale * longest_side);
  return std::string(text);
}

}  // namespace pushpull::app
