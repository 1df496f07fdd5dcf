// `pushpull review`: the headset loop. Opens an OpenXR session (xr::Session), hands its Vulkan device to the
// renderer (Context::wrap), places the model on the stage (T_stage_model), and runs frames: input ->
// push/pull interaction -> deform::Service (never waited on) -> the newest snapshot drawn into both eyes ->
// xrEndFrame. On exit it waits for the service to finish and writes the committed model (--out) and the event
// log. Thread-safety: run_review runs on the calling thread; the service has its own worker.
#pragma once

#include "commit_watch.hpp"
#include "head_anchor.hpp"
#include "life_size.hpp"
#include "press_hold.hpp"
#include "size_change.hpp"

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pushpull::app {

// Lengths typed in life-size metres (life_size.hpp).
struct ReviewCommandOptions {
  std::string model;
  std::string method = "asan";
  double mu = 100.0;  // ASAN stiffness ratio (deform::DeformOptions::mu)
  // deform::DeformOptions::smooth_start_min_free; empty: the solver's default. A replay: the recording's, -1
  // when it has none (the solves of versions before the smooth start began from rest).
  std::optional<int> smooth_start_min_free;
  // deform::DeformOptions::coarse_start_min_free, likewise (-1 for a recording that has none: its solves
  // never started coarse-to-fine).
  std::optional<int> coarse_start_min_free;
  double handle_radius_m = 0.05;
  double roi_radius_m = 0.6;
  std::vector<double> up{0.0, 1.0, 0.0};     // model frame
  std::vector<double> front{0.0, 0.0, 1.0};  // model frame
  // Whether --up was given: a plain mesh file (OFF, OBJ, PLY) names no up axis, and one standing on its thin
  // side under the default up is said (review_setup.cpp). A replay gives the recording's.
  bool up_given = false;
  double distance_m = 0.6;
  std::vector<int> eye_size;  // W H, empty: the runtime's recommendation
  int samples = 4;
  // Whether --samples was given. Desktop mode on a CPU renderer (lavapipe) draws without MSAA unless it was:
  // 1200 x 750 took 166 ms a frame with 4 samples and 66 with 1 (AsamVehicle).
  bool samples_given = false;
  std::string colour = "displacement";
  std::string out;
  std::string events;
  bool benchmark = false;
  // No status lines on stdout (start, press/commit, wrote); errors and warnings still show.
  bool quiet = false;
  // The method stays `method` (keys and the menu do not change it; replay --method).
  bool fixed_method = false;
  // The headset review's solver thread: this niceness (deform::ServiceOptions::worker_nice, 0-19), or the
  // idle scheduling class (worker_idle). --solver-priority: the niceness or "idle".
  bool solver_idle = false;
  int solver_nice = 10;
  // The headset review's CPUs for the solver (solver_cpus.hpp: "none", "auto" or a list); the frame loop
  // keeps the others. --solver-cpus.
  std::string solver_cpus = "none";
  // After a lost session: how long to wait for the headset to come back before ending (s; 0: end at once).
  double reconnect_s = 30.0;
  // At the start: how long a runtime whose headset has not connected yet (a streaming runtime before the
  // headset joins, a runtime still bringing its headset up) is given before the desktop window opens (s).
  double headset_wait_s = 3.0;
  bool validation = false;  // Vulkan validation layer on the runtime's instance; any message fails the run
  bool mirror = false;      // the supervisor's GLFW window
  bool desktop = false;     // no headset: the window is the workspace (desktop_loop.hpp)
  int frames = 0;           // desktop mode: stop after this many frames (0: when the window closes)
  std::vector<int> mirror_size{960, 540};
  LifeSizeOptions life_size;
  // The session recording (session_recorder.hpp); empty: default_recording_path().
  std::string record;
  // Called on the loop's thread for every commit the service finished, in order, as soon as the loop sees it
  // (and the last ones after the service went idle at the end). Used by `pushpull replay`.
  std::function<void(const CommitRecord&)> on_commit;
  // A replay: the format of its recording (session_recorder.hpp), whose review's behaviour it reproduces.
  // Before format 6 two-grip scaling was about the hands' midpoint, and a trigger the grip or the menu panel
  // gave back still pulled could press at once; before format 7 a trackpad steered the sizes while touched;
  // before format 8 a grip squeezed during a drag grabbed the model when the drag ended.
  int behaviour_of_format = 8;
  // Called like on_commit for every push/pull the service could not commit (the model stayed as it was).
  std::function<void(const FailedCommit&)> on_failed_commit;
  // Headset loop: called once per frame with the recording's time of the frame (s), after its input was read
  // (`pushpull replay`'s progress bar).
  std::function<void(double t)> on_frame;
  // Headset loop (replay): method changes made with a key during the recorded session, (recording time s,
  // method name) in time order; each applies after the gesture of the frame at that time, as the key did.
  std::vector<std::pair<double, std::string>> method_changes;
  // Headset loop (replay): colour-map changes (recording time s, colour_name()), applied likewise.
  std::vector<std::pair<double, std::string>> colour_changes;
  // Headset loop (replay): sizes the recorded session's keys set, applied before the gesture of their frame.
  std::vector<SizeChange> size_changes;
  // Headset loop (replay): the times (s) the recorded reviewer cancelled a drag (Esc mid-drag in the desktop
  // window), in order; each cancels the drag in progress before the gesture of its frame, as the key did.
  std::vector<double> cancels;
  // Headset loop (replay): the undo and redo the recorded session sent ("undo"/"redo" records: time s, kind).
  // Set: an undo or redo button sends the step exactly when the recording did at that frame (live, whether it
  // is sent depends on whether the service was busy, history_steps.hpp); unset: decided live.
  std::optional<std::vector<std::pair<double, std::string>>> history_steps;
  // Headset loop (replay): the presses the recorded session held back (press_hold.hpp), in time order. Set:
  // a press held back while solving is let through at exactly the recorded frame (the loop waits for the
  // service there) and any other press at once (waiting too), as the recorded loop did. Unset (live): a press
  // is held back until the service is idle, and no frame waits.
  std::optional<std::vector<PressHold>> press_holds;
  // Headset loop: where the model is anchored to the reviewer (head_anchor.hpp). Live (unset): at the first
  // frame the head is located. Set (replay): the recorded anchor at its frame, or none when the recording has
  // none (an older format, a desktop session, a head never located): the model stays where the header put it.
  std::optional<std::optional<HeadAnchor>> recorded_anchor;
  // Headset loop: whether to draw the eyes of the frame at recording time t (s); empty: every frame. Frames
  // not drawn end without layers. `pushpull replay` draws only the frames the simulated runtime captures: the
  // loop computes the same either way, and a software rasterizer spends its time on the frames that are kept.
  std::function<bool(double t)> draw_frame;
  // With draw_frame: a drawn frame first waits for the deformation service to finish (replay: captured eyes
  // show the settled result, the same on every run). Commits do not depend on it.
  bool settle_drawn_frames = false;
  // Live: Ctrl-C or SIGTERM end the review as Esc does (interrupt_requests.hpp). A replay leaves them the
  // default action (it would otherwise report the commits the interrupted loop never reached as mismatches).
  bool end_on_interrupt = true;
};

// Throws CommandError (no runtime or headset: one line saying which runtime was looked for and how to point
// at one) or the module's errors naming the failing call.
void run_review(const ReviewCommandOptions& options);

}  // namespace pushpull::app
