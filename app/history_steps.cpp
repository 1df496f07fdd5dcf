#include "history_steps.hpp"

namespace pushpull::app {

bool request_history_step(deform::Service& service, HistoryStep step) {
  if (service.idle()) {
    const EditCounts counts = edit_counts(service);
    if (step == HistoryStep::Undo && counts.undone == counts.edits) return false;
    if (step == HistoryStep::Redo && counts.undone == 0) return false;
  }
  send_history_step(service, step);
  return true;
}

void send_history_step(deform::Service& service, HistoryStep step) {
  if (step == HistoryStep::Undo)
    service.undo();
  else
    service.redo();
}

const char* nothing_to(HistoryStep step) {
  return step == HistoryStep::Undo ? "nothing to undo" : "nothing to redo";
}

EditCounts edit_counts(const deform::Service& service) {
  // Two reads: the worker may move the position between them; clamped so the counts stay consistent.
  const std::size_t size = service.history_size();
  const std::size_t position = service.history_position();
  EditCounts counts;
  counts.edits = size > 0 ? size - 1 : 0;
  counts.undone = position < counts.edits ? counts.edits - position : 0;
  return counts;
}

std::string edit_counts_text(EditCounts counts) {
  if (counts.edits == 0) return "no edits";
  std::string text = std::to_string(counts.edits) + (counts.edits == 1 ? " edit" : " edits");
  if (counts.undone > 0) text += ", " + std::to_string(counts.undone) + " undone";
  return text;
}

}  // namespace pushpull::app
