#include "solver_state.hpp"

namespace pushpull::app {

bool is_drag_preview(const deform::Snapshot& s) {
  return s.kind == deform::Snapshot::Kind::Preview;
}

const char* solver_state(const deform::Snapshot& s) {
  if (!is_drag_preview(s)) return "waiting";
  return s.final ? (s.converged ? "converged" : "not converged") : "solving";
}

int drag_iterations(const deform::Snapshot& s) {
  return is_drag_preview(s) ? s.iteration : 0;
}

}  // namespace pushpull::app
