#include "window_hud.hpp"

#include "solver_state.hpp"

#include <cstdio>

namespace pushpull::app {

void announce(TimedNotice& notice, const std::string& text, double now, bool print) {
  notice.show(text, now);
  if (print) std::printf("pushpull review: %s\n", text.c_str());
}

std::vector<std::string> window_hud_lines(const ReviewInteraction& interaction,
                                          const deform::Snapshot& snapshot, const LifeSize& life,
                                          const std::string& colour, const std::string& view_mode,
                                          const std::vector<std::string>& keys, const std::string& history,
                                          const std::string& notice) {
  const std::string method(deform::method_name(interaction.method()));
  char state[256];
  if (snapshot.kind == deform::Snapshot::Kind::Error) {
    // The error is its solve's method's: after M the next push/pull's method is ready, the error said as the
    // old one's ("arap-sr  error: the energy is negative" read as arap-sr's failure).
    const std::string failed(deform::method_name(snapshot.method));
    if (failed == method || interaction.dragging())
      std::snprintf(state, sizeof state, "%s  error: %s", failed.c_str(), error_gist(snapshot.error).c_str());
    else
      std::snprintf(state, sizeof state, "%s  ready  (%s failed: %s)", method.c_str(), failed.c_str(),
                    error_gist(snapshot.error).c_str());
  } else if (interaction.dragging()) {
    std::snprintf(state, sizeof state, "%s  |d| %.1f mm  %d it  %s", method.c_str(),
                  life.to_mm(interaction.current_d().norm()), drag_iterations(snapshot),
                  solver_state(snapshot));
  } else if (!snapshot.final) {
    std::snprintf(state, sizeof state, "%s  solving  %d it", method.c_str(), snapshot.iteration);
  } else {
    // Just after a commit: what its own solve did (it starts cold, so it differs from the last preview's).
    const std::string& said = notice.empty() ? history : notice;
    if (snapshot.kind == deform::Snapshot::Kind::Committed)
      std::snprintf(state, sizeof state, "%s  ready  %s  (commit: %d it, %s)", method.c_str(), said.c_str(),
                    snapshot.iteration, snapshot.converged ? "converged" : "not converged");
    else
      std::snprintf(state, sizeof state, "%s  ready  %s", method.c_str(), said.c_str());
  }
  std::string first = state;
  // A notice shows in every state (e.g. a key pressed mid-drag: "the method changes between drags").
  if (!notice.empty() &&
      (interaction.dragging() || !snapshot.final || snapshot.kind == deform::Snapshot::Kind::Error))
    first += "  " + notice;
  // The sizes a press would grab with, in every state (shown by the hover readout only on the surface).
  char sizes[96];
  std::snprintf(sizes, sizeof sizes, "   handle %.0f mm  region %.0f mm",
                life.to_mm(interaction.handle_radius()), life.to_mm(interaction.roi_radius()));
  std::vector<std::string> lines{
      first, "colour: " + colour + (view_mode.empty() ? "" : "   view: " + view_mode) + sizes};
  lines.insert(lines.end(), keys.begin(), keys.end());
  return lines;
}

std::string window_title(const std::string& name, deform::Method method, bool dragging,
                         const deform::Snapshot& snapshot, const LifeSize& life, const std::string& colour,
                         const std::string& view_mode, const std::string& history,
                         const std::string& notice) {
  char text[320];
  if (dragging)
    std::snprintf(text, sizeof text, "%s | %s (dragging) | |d| %.1f mm | %d it %s | %s", name.c_str(),
                  std::string(deform::method_name(method)).c_str(),
                  life.to_mm(is_drag_preview(snapshot) ? snapshot.d.norm() : 0.0), drag_iterations(snapshot),
                  solver_state(snapshot), colour.c_str());
  else
    std::snprintf(text, sizeof text, "%s | %s | %s | %s", name.c_str(),
                  std::string(deform::method_name(method)).c_str(),
                  (notice.empty() ? history : notice).c_str(), colour.c_str());
  std::string title = text;
  if (dragging && !notice.empty()) title += " | " + notice;
  return view_mode.empty() ? title : title + " | " + view_mode;
}

}  // namespace pushpull::app
