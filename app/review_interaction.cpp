#include "review_interaction.hpp"

#include "drag_notes.hpp"
#include "solver_state.hpp"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace pushpull::app {
namespace {

// After a cancelled drag, a hand's trigger at or below this is seen released, and the hand may press again.
constexpr float kRearmTrigger = 0.1f;

xr::GestureOptions gesture_options(double scale) {
  xr::GestureOptions o;
  o.min_displacement_m = 1e-4 / scale;  // the gesture sees model units
  return o;
}

glm::dvec3 to_glm(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

std::vector<std::string> readout_lines(const ReviewInteraction& interaction, const deform::Snapshot& s,
                                       const LifeSize& life, bool press_held, const std::string& notice) {
  char a[96], b[96];
  const std::string method(deform::method_name(interaction.method()));
  if (!interaction.dragging() && press_held) return {"press held", "the last commit is solving"};
  if (!interaction.dragging()) {
    std::snprintf(a, sizeof a, "%s%s%s", method.c_str(), notice.empty() ? "" : "  ", notice.c_str());
    std::snprintf(b, sizeof b, "handle %.0f mm  region %.0f mm", life.to_mm(interaction.handle_radius()),
                  life.to_mm(interaction.roi_radius()));
    return {a, b};
  }
  std::snprintf(a, sizeof a, "|d| %.1f mm", life.to_mm(interaction.current_d().norm()));
  if (s.kind == deform::Snapshot::Kind::Error) return {a, method + "  error:", error_gist(s.error)};
  std::snprintf(b, sizeof b, "%s  %d it  %s", method.c_str(), drag_iterations(s), solver_state(s));
  std::vector<std::string> lines{a, b};
  if (!notice.empty()) lines.push_back(notice);  // e.g. a key pressed mid-drag
  for (std::string& note : drag_notes(interaction.current_d().norm(), interaction.handle_radius(), s))
    lines.push_back(std::move(note));
  return lines;
}

deform::Method next_method(deform::Method method) {
  const auto& all = deform::kAllMethods;
  const auto it = std::find(all.begin(), all.end(), method);
  return it == all.end() || it + 1 == all.end() ? all.front() : *(it + 1);
}

ReviewInteraction::ReviewInteraction(deform::Service& service, const deform::Mesh& rest, StagePlacement placement,
                                     InteractionOptions options)
    : service_(service),
      placement_(std::move(placement)),
      options_(std::move(options)),
      committed_(rest),
      surface_graph_(rest),
      bvh_(rest.V, rest.F),
      gestures_{xr::PushPullGesture(gesture_options(options_.scale)),
                xr::PushPullGesture(gesture_options(options_.scale))} {}

std::optional<deform::TriangleBvh::Hit> ReviewInteraction::hit(const Eigen::Vector3d& origin_stage,
                                                               const Eigen::Vector3d& direction_stage) const {
  return bvh_.ray_hit(committed_.V, placement_.to_model_point(origin_stage),
                      placement_.to_model_vector(direction_stage));
}

void ReviewInteraction::sync_committed(const deform::Snapshot& snapshot) {
  if (snapshot.revision == bvh_revision_ || !snapshot.rest) return;
  if (bvh_revision_ != 0 || snapshot.rest->V != committed_.V) {
    committed_.V = snapshot.rest->V;
    bvh_.refit(committed_.V);
    hover_handle_cache_.reset();
    // What the hands aim at on the new shape (shown at once, not one frame late, and the same whichever frame
    // the committed shape arrived at).
    for (size_t h = 0; h < 2; ++h) hovers_[h] = rays_[h] ? hit(rays_[h]->first, rays_[h]->second) : std::nullopt;
  }
  bvh_revision_ = snapshot.revision;
}

void ReviewInteraction::submit(const Eigen::Vector3d& d) {
  if (submitted_ && d == last_d_) return;  // the newest request already says this
  deform::Request request;
  request.drag = drag_id_;
  request.handle = deform::SurfaceHandle{p0_, options_.handle_radius};
  request.region.max_distance = options_.roi_radius;
  request.d = d;
  request.options = options_.solver;
  service_.submit(std::move(request));
  last_d_ = d;
  submitted_ = true;
}

bool ReviewInteraction::would_press(const std::array<HandSample, 2>& hands) const {
  if (dragging()) return false;
  for (size_t h = 0; h < 2; ++h) {
    const HandSample& in = hands[h];
    if (armed_[h] && in.tracked && !gestures_[h].trigger_down() &&
        in.trigger >= gestures_[h].options().press_threshold)
      return true;
  }
  return false;
}

bool ReviewInteraction::trigger_held(const std::array<HandSample, 2>& hands) const {
  for (size_t h = 0; h < 2; ++h)
    if (hands[h].trigger > gestures_[h].options().release_threshold) return true;
  return false;
}

std::vector<InteractionEvent> ReviewInteraction::update(const std::array<HandSample, 2>& hands) {
  std::vector<InteractionEvent> events;
  for (int h = 0; h < 2; ++h) {
    const HandSample& in = hands[size_t(h)];
    rays_[size_t(h)] = in.tracked ? std::optional(std::pair(in.origin_stage, in.direction_stage)) : std::nullopt;
    hovers_[size_t(h)] = in.tracked ? hit(in.origin_stage, in.direction_stage) : std::nullopt;
    // After a cancelled drag (session or focus lost) a trigger still held does not grab again: it must be let go.
    if (!armed_[size_t(h)] && in.tracked && in.trigger <= kRearmTrigger) armed_[size_t(h)] = true;
    // One drag at a time: the other hand's gesture sees a released trigger while one hand drags.
    xr::ControllerSample sample;
    sample.trigger = armed_[size_t(h)] && (drag_hand_ < 0 || drag_hand_ == h) ? in.trigger : 0.0f;
    sample.tracked = in.tracked;
    sample.hand_position = to_glm(placement_.to_model_point(in.origin_stage));
    if (hovers_[size_t(h)]) sample.surface_hit = to_glm(hovers_[size_t(h)]->point);
    const xr::GestureEvent e = gestures_[size_t(h)].update(sample);
    switch (e.kind) {
      case xr::GestureEventKind::Pressed:
        if (const auto pressed = begin_drag(h, *hovers_[size_t(h)])) events.push_back(*pressed);
        break;
      case xr::GestureEventKind::Dragged:
        submit(to_eigen(e.displacement()));
        break;
      case xr::GestureEventKind::Released:
        submit(to_eigen(e.displacement()));
        events.push_back(finish(true));
        break;
      case xr::GestureEventKind::Cancelled:
        events.push_back(finish(false));
        break;
      case xr::GestureEventKind::None:
        break;
    }
  }
  return events;
}

void ReviewInteraction::scale_sizes(double handle_factor, double region_factor) {
  if (!(handle_factor > 0.0) || !(region_factor > 0.0)) return;
  set_sizes(options_.handle_radius * handle_factor, options_.roi_radius * region_factor);
}

void ReviewInteraction::set_sizes(double handle_radius, double roi_radius) {
  if (dragging() || !(handle_radius > 0.0) || !(roi_radius > 0.0)) return;
  const double lo = 1e-3 / options_.scale, hi = 10.0 / options_.scale;
  options_.handle_radius = std::clamp(handle_radius, lo, hi);
  options_.roi_radius = std::clamp(roi_radius, lo, hi);
}

void ReviewInteraction::set_method(deform::Method method) {
  if (!dragging()) options_.solver.method = method;
}

std::optional<InteractionEvent> ReviewInteraction::begin_drag(int hand, const deform::TriangleBvh::Hit& hit) {
  if (dragging()) return std::nullopt;
  drag_hand_ = hand;
  ++drag_id_;
  submitted_ = false;
  last_d_.setZero();
  p0_ = {hit.face, hit.point};
  InteractionEvent out;
  out.kind = InteractionEvent::Kind::Pressed;
  out.method = method();
  out.hand = hand;
  out.face = p0_.face;
  out.p0 = p0_.point;
  return out;
}

InteractionEvent ReviewInteraction::finish(bool commit) {
  InteractionEvent out;
  out.method = method();
  out.hand = drag_hand_;
  out.face = p0_.face;
  out.p0 = p0_.point;
  out.d = last_d_;
  if (commit) {
    out.kind = InteractionEvent::Kind::Committed;
    out.request = service_.commit();
  } else {
    out.kind = InteractionEvent::Kind::Cancelled;
    service_.cancel();
  }
  drag_hand_ = -1;
  return out;
}

Eigen::Vector3d ReviewInteraction::face_normal(int face) const {
  const Eigen::MatrixXd& V = committed_.V;
  const Eigen::MatrixXi& F = committed_.F;
  const Eigen::Vector3d a = V.row(F(face, 0)), b = V.row(F(face, 1)), c = V.row(F(face, 2));
  return (b - a).cross(c - a).normalized();
}

const std::vector<int>& ReviewInteraction::hover_handle(int hand) {
  static const std::vector<int> kNone;
  const auto& hover = hovers_.at(size_t(hand));
  if (!hover || dragging()) return kNone;
  if (hover_handle_cache_ && hover_handle_cache_->face == hover->face && hover_handle_cache_->point == hover->point &&
      hover_handle_cache_->radius == options_.handle_radius)
    return hover_handle_cache_->vertices;
  hover_handle_cache_ = HoverHandle{hover->face, hover->point, options_.handle_radius,
                                    surface_graph_.handle(committed_.V, {hover->face, hover->point},
                                                          options_.handle_radius)};
  return hover_handle_cache_->vertices;
}

std::optional<InteractionEvent> ReviewInteraction::cancel() {
  if (drag_hand_ < 0) return std::nullopt;
  // Reset the gesture: a sample with tracking lost ends its drag.
  xr::ControllerSample lost;
  lost.tracked = false;
  gestures_[size_t(drag_hand_)].update(lost);
  armed_ = {false, false};
  return finish(false);
}

}  // namespace pushpull::app
