// The review's push/pull interaction: controller aim rays -> BVH hit on the committed surface (p0) -> the
// push-pull gesture -> requests to deform::Service every frame of a drag, commit on release, cancel on a
// click, lost tracking or a lost session. Knows neither OpenXR nor the renderer: the loop feeds it hand
// samples in stage space and it talks to the service.
//
// Frames and units: samples are in stage space (metres); p0, d and the handle radius are model space, file
// units (the placement's inverse maps stage to model). The BVH holds the committed shape (rest of the newest
// snapshot), refitted when the committed revision changes (commit, undo, redo).
// Ownership: borrows the Service (outlives this). Thread-safety: one thread (the frame loop).
#pragma once

#include "error_gist.hpp"
#include "life_size.hpp"
#include "stage_placement.hpp"

#include "pushpull/deform/service.hpp"
#include "pushpull/deform/surface_point.hpp"
#include "pushpull/deform/triangle_bvh.hpp"
#include "pushpull/xr/push_pull_gesture.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

struct HandSample {
  bool tracked = false;
  float trigger = 0.0f;             // 0..1
  Eigen::Vector3d origin_stage{0, 0, 0};     // aim ray origin, stage, metres
  Eigen::Vector3d direction_stage{0, 0, -1};  // aim ray direction, stage (unit)
  Eigen::Vector3d up_stage{0, 1, 0};          // the controller's +Y, stage (unit)
};

struct InteractionOptions {
  double handle_radius = 0.05;  // model units, along the surface from p0
  double roi_radius = 0.6;      // model units, region grown from the handle
  deform::DeformOptions solver;
  double scale = 1.0;  // metres per model unit (the gesture's click threshold is 0.1 mm at life size)
};

// Something the reviewer did, for the log and the HUD.
struct InteractionEvent {
  enum class Kind { Pressed, Committed, Cancelled };
  Kind kind = Kind::Pressed;
  int hand = 0;  // 0 left, 1 right
  int face = -1;
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero();  // model space
  Eigen::Vector3d d = Eigen::Vector3d::Zero();   // model space (the last one submitted)
  std::uint64_t request = 0;                     // Committed: the committed request (Service::commit)
  deform::Method method = deform::Method::Asan;  // the drag's method (it does not change mid-drag)
};

class ReviewInteraction;

// The readout shown by the hand (headset) or the cursor (desktop): while dragging "|d| 70.7 mm" and the
// method, iterations and solver state ("asan  10 it  converged", "waiting", "solving", or the error) and the
// drag's notes (drag_notes.hpp: steep, the surface overshooting, a whole part moving); while aiming the
// method and the handle and region sizes, or with press_held (a press held back until the last commit lands)
// that it waits; a notice ("nothing to undo") follows the method while aiming, and is a line of its own while
// dragging. Lengths in life-size mm.
[[nodiscard]] std::vector<std::string> readout_lines(const ReviewInteraction& interaction,
                                                     const deform::Snapshot& s, const LifeSize& life,
                                                     bool press_held = false, const std::string& notice = "");

// The method after `method` in deform::kAllMethods, the first after the last (a key cycles through them).
[[nodiscard]] deform::Method next_method(deform::Method method);

class ReviewInteraction {
 public:
  ReviewInteraction(deform::Service& service, const deform::Mesh& rest, StagePlacement placement,
                    InteractionOptions options);

  // One frame: both hands. Returns what happened (press, commit, cancel), in order.
  std::vector<InteractionEvent> update(const std::array<HandSample, 2>& hands);
  // Thumbstick between drags: scales the handle radius and the region radius by these factors (> 0), within
  // [1 mm, 10 m] at life size. Ignored while dragging (a drag keeps its setup).
  void scale_sizes(double handle_factor, double region_factor);
  // Both radii as given (model units; a replay's recorded sizes), clamped as scale_sizes clamps; not while
  // dragging.
  void set_sizes(double handle_radius, double roi_radius);
  // The model was moved on the stage (grip). Takes effect for the next samples; call between drags.
  void set_placement(const StagePlacement& placement) { placement_ = placement; }
  // The method of the next drag (a drag keeps its method). Ignored while dragging.
  void set_method(deform::Method method);
  [[nodiscard]] deform::Method method() const { return options_.solver.method; }
  [[nodiscard]] double handle_radius() const { return options_.handle_radius; }
  [[nodiscard]] double roi_radius() const { return options_.roi_radius; }
  // The committed shape's unit face normal (model space) of a face from hit().
  [[nodiscard]] Eigen::Vector3d face_normal(int face) const;
  // Drops a drag in progress (session lost, focus lost): the service shows the committed state again. A trigger
  // still held afterwards does not start another drag: each hand's trigger must be seen released first.
  std::optional<InteractionEvent> cancel();
  // Between drags: a trigger pulled now must be let go before it presses (the grip or the menu panel had it,
  // and gives it back still pulled). No effect on a trigger already released.
  void require_release() {
    if (drag_hand_ < 0) armed_ = {false, false};
  }
  // The committed shape changed (newest snapshot's rest): refits the BVH when its revision is new.
  void sync_committed(const deform::Snapshot& snapshot);

  [[nodiscard]] bool dragging() const { return drag_hand_ >= 0; }
  [[nodiscard]] int drag_hand() const { return drag_hand_; }
  // Whether update(hands) would see a trigger go down: a tracked, armed hand whose trigger reaches the press
  // threshold while its gesture's trigger is up, and no drag. Whether it grabs also depends on the aim; this
  // does not look at the surface, so the answer depends on the input alone (not on when a commit landed).
  [[nodiscard]] bool would_press(const std::array<HandSample, 2>& hands) const;
  // Whether some hand's trigger is still above the release threshold (a press held back is kept).
  [[nodiscard]] bool trigger_held(const std::array<HandSample, 2>& hands) const;
  // Where each hand's ray meets the committed surface (model space), for the cursor.
  [[nodiscard]] const std::array<std::optional<deform::TriangleBvh::Hit>, 2>& hovers() const { return hovers_; }
  [[nodiscard]] const Eigen::Vector3d& current_d() const { return last_d_; }
  // The vertices a press of `hand` would grab now (model vertices of its hover hit within the handle radius,
  // along the surface, as the drag's handle will be); empty without a hit or during a drag. Cached per hit
  // point and radius: O(handle patch) when the aim moves, nothing when it does not.
  [[nodiscard]] const std::vector<int>& hover_handle(int hand);
  // Ray hit on the committed surface in model space (exposed for the benchmark).
  [[nodiscard]] std::optional<deform::TriangleBvh::Hit> hit(const Eigen::Vector3d& origin_stage,
                                                            const Eigen::Vector3d& direction_stage) const;

 private:
  // Grabs the surface at `hit` (model space) for `hand`'s gesture; nullopt while a drag runs.
  std::optional<InteractionEvent> begin_drag(int hand, const deform::TriangleBvh::Hit& hit);
  void submit(const Eigen::Vector3d& d);
  InteractionEvent finish(bool commit);  // commit or cancel the running drag

  deform::Service& service_;
  StagePlacement placement_;
  InteractionOptions options_;
  deform::Mesh committed_;  // the committed shape (rest of the newest snapshot)
  deform::SurfaceGraph surface_graph_;  // its connectivity, for the handle-to-be under the aim (built once)
  struct HoverHandle {
    int face = -1;
    Eigen::Vector3d point;
    double radius = 0.0;
    std::vector<int> vertices;
  };
  std::optional<HoverHandle> hover_handle_cache_;
  deform::TriangleBvh bvh_;
  std::uint64_t bvh_revision_ = 0;
  std::array<xr::PushPullGesture, 2> gestures_;
  std::array<std::optional<deform::TriangleBvh::Hit>, 2> hovers_;
  std::array<bool, 2> armed_{true, true};  // the trigger may press (false after a cancel until seen released)
  std::array<std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>, 2> rays_;  // last aim rays, stage
  int drag_hand_ = -1;
  std::uint64_t drag_id_ = 0;
  deform::SurfacePoint p0_;
  Eigen::Vector3d last_d_ = Eigen::Vector3d::Zero();
  bool submitted_ = false;
};

}  // namespace pushpull::app
