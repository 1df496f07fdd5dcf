#include "review_loop.hpp"

#include "drag_notes.hpp"

#include "commands.hpp"
#include "commit_reports.hpp"
#include "desktop_loop.hpp"
#include "frame_stats.hpp"
#include "grab_placement.hpp"
#include "hand_sample.hpp"
#include "history_steps.hpp"
#include "interrupt_requests.hpp"
#include "orbit_control.hpp"
#include "review_end.hpp"
#include "review_interaction.hpp"
#include "review_menu.hpp"
#include "review_scene.hpp"
#include "review_setup.hpp"
#include "session_recorder.hpp"
#include "size_steering.hpp"
#include "solver_cpus.hpp"
#include "stage_placement.hpp"
#include "supervisor_mirror.hpp"
#include "vulkan_validation.hpp"
#include "window_hud.hpp"
#include "world_label.hpp"

#include "pushpull/assets/model.hpp"
#include "pushpull/deform/cpu_affinity.hpp"
#include "pushpull/deform/file_output.hpp"
#include "pushpull/deform/metrics.hpp"
#include "pushpull/deform/service.hpp"
#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/mirror_window.hpp"
#include "pushpull/renderer/renderer.hpp"
#include "pushpull/xr/input.hpp"
#include "pushpull/xr/session.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <numeric>
#include <thread>

namespace pushpull::app {
namespace {

using Clock = std::chrono::steady_clock;

// The controller's heading about stage +Y: where its ray points, or, when it points nearly straight up or
// down, where its top (+Y) faces (the ray's heading is noise there).
double heading(const HandSample& s) {
  const Eigen::Vector3d& f = s.direction_stage;
  const Eigen::Vector3d h =
      std::hypot(f.x(), f.z()) > 0.3 ? f : (f.y() < 0.0 ? s.up_stage : Eigen::Vector3d(-s.up_stage));
  return std::atan2(-h.x(), -h.z());
}

// The recording's time of a replayed change.
double change_time(const std::pair<double, std::string>& change) {
  return change.first;
}
double change_time(const SizeChange& change) {
  return change.time;
}
double change_time(double time) {
  return time;
}

// Replay: the recorded changes due by `until`, from `next` on, each given to apply in order.
template <class Change, class Apply>
void apply_due(const std::vector<Change>& changes, std::size_t& next, double until, Apply apply) {
  while (next < changes.size() && change_time(changes[next]) <= until) apply(changes[next++]);
}

}  // namespace

void run_review(const ReviewCommandOptions& o) {
  // The desktop window needs a display: said before the model loads (a large model takes seconds).
  if (o.desktop && std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
    throw CommandError(
        "desktop mode: no display (DISPLAY and WAYLAND_DISPLAY are unset; use xvfb-run without one)");
  const ReviewSetup setup = prepare_review(o);
  const LifeSize& life = setup.life;
  const assets::Model& model = setup.model;
  const std::shared_ptr<const deform::Mesh>& rest = setup.rest;
  const StagePlacement& placement = setup.placement;
  const InteractionOptions& interaction_options = setup.interaction;
  const ReviewColour colour = setup.colour;
  if (o.desktop) return run_desktop(o, setup);

  xr::SessionOptions session_options;
  session_options.require_vulkan13_features = [](VkPhysicalDeviceVulkan13Features& f) {
    renderer::Context::require_features(f);
  };
  session_options.headset_wait_s = o.headset_wait_s;
  if (o.eye_size.size() == 2) {
    session_options.eye_width = uint32_t(o.eye_size[0]);
    session_options.eye_height = uint32_t(o.eye_size[1]);
  }
  if (o.mirror) {
    session_options.eye_transfer_source = true;  // headset-eye mode copies the left eye into the window
    try {
      session_options.vulkan_instance_extensions = renderer::MirrorWindow::required_instance_extensions();
    } catch (const std::exception& e) {
      throw CommandError(std::string("--mirror: ") + e.what());
    }
    session_options.vulkan_device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  if (o.validation) {
    session_options.vulkan_layers = validation_layers();
    for (const auto& e : validation_extensions()) session_options.vulkan_instance_extensions.push_back(e);
  }
  // --solver-cpus: the frame thread moves to the frames' CPUs before the runtime makes the Vulkan device, so
  // the threads the device starts (lavapipe's) stay there too; the solver's threads go to theirs.
  const std::vector<int> all_cpus = deform::allowed_cpus();
  std::optional<CpuSplit> cpus;
  if (o.solver_cpus != "none" && all_cpus.empty()) {
    std::fprintf(stderr,
                 "pushpull review: --solver-cpus %s: this system does not say which CPUs threads may run on; "
                 "ignored, the solver shares them with the frames\n",
                 o.solver_cpus.c_str());
  } else {
    try {
      cpus = split_cpus(o.solver_cpus, all_cpus);
    } catch (const std::invalid_argument& e) {
      throw CommandError("--solver-cpus " + o.solver_cpus + ": " + e.what());
    }
    if (!cpus && o.solver_cpus == "auto")
      std::fprintf(stderr, "pushpull review: --solver-cpus auto: one CPU (%s), nothing to split\n",
                   cpu_list_text(all_cpus).c_str());
  }
  if (cpus && !deform::pin_calling_thread(cpus->frames)) {
    std::fprintf(
        stderr,
        "pushpull review: --solver-cpus %s: the frame thread could not be pinned to CPU %s (%s); the "
        "solver shares the CPUs with the frames\n",
        o.solver_cpus.c_str(), cpu_list_text(cpus->frames).c_str(), std::strerror(errno));
    cpus.reset();
  }
  // A CPU renderer (lavapipe, llvmpipe) starts a thread per CPU of the machine unless told otherwise: as many
  // as the frames have, unless the user said.
  if (cpus && std::getenv("LP_NUM_THREADS") == nullptr)
    (void)::setenv("LP_NUM_THREADS", std::to_string(cpus->frames.size()).c_str(), 0);
  std::optional<xr::Session> session;
  try {
    session.emplace(session_options);
  } catch (const xr::RuntimeUnavailable& e) {
    // No runtime or headset: one line saying so, then the desktop window where there is a display.
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
      throw CommandError(e.what());
    std::fprintf(stderr, "pushpull review: %s; opening the desktop window instead\n", e.what());
    if (cpus) (void)deform::pin_calling_thread(all_cpus);  // the desktop window shares the CPUs
    return run_desktop(o, setup);
  }
  xr::Session& xr = *session;
  if (!o.quiet)
    std::printf("pushpull review: %s on %s (OpenXR runtime \"%s\"), %ux%u per eye in %s, %s space\n",
                o.model.c_str(), xr.system_name().c_str(), xr.runtime_name().c_str(), xr.eye(0).width(),
                xr.eye(0).height(),
                xr.eye(0).format() == VK_FORMAT_B8G8R8A8_SRGB ? "B8G8R8A8_SRGB" : "R8G8B8A8_SRGB",
                xr.stage_is_local() ? "LOCAL (no STAGE)" : "STAGE");
  if (cpus && !o.quiet)
    std::printf("pushpull review: the solver runs on CPU %s, the frames on CPU %s\n",
                cpu_list_text(cpus->solver).c_str(), cpu_list_text(cpus->frames).c_str());

  EventLog log(o.events, !o.quiet);
  log.write_start(o, setup, xr.runtime_name());
  SessionRecorder recorder(o.record.empty() ? default_recording_path() : o.record, !o.record.empty());
  {
    RecordingContext context;
    context.runtime = xr.runtime_name();
    context.view_configuration = "XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO";
    context.eye_width = int(xr.eye(0).width());
    context.eye_height = int(xr.eye(0).height());
    recorder.write_header(o, setup, context);
  }
  if (recorder.recording() && !o.quiet)
    std::printf("pushpull review: recording the session to %s\n", recorder.path().c_str());

  std::optional<VulkanValidation> validation;
  if (o.validation) validation.emplace(xr.vulkan().instance);
  {
    const xr::VulkanDevice& vk = xr.vulkan();
    renderer::Context context = renderer::Context::wrap(
        {vk.instance, vk.physical_device, vk.device, vk.queue_family_index, vk.queue});
    renderer::RendererOptions renderer_options;
    renderer_options.samples = VkSampleCountFlagBits(o.samples);
    renderer_options.frames_in_flight = 2;  // loop frames: the eyes and the mirror are one render_frame()
    renderer::Renderer renderer(context, renderer_options);
    std::optional<SupervisorMirror> mirror;
    if (o.mirror)
      mirror.emplace(context, renderer, uint32_t(o.mirror_size[0]), uint32_t(o.mirror_size[1]),
                     stage_bounds(rest->V, placement));
    std::optional<std::array<xr::EyeView, 2>> last_eyes;
    // Live: snapshots become vertex data on the scene's own thread (the frame thread only copies them). A
    // replay converts on this thread, so every drawn frame shows exactly the settled snapshot.
    ReviewScene scene(renderer, model, placement, colour, life.scale(), /*async=*/!o.settle_drawn_frames,
                      cpus ? cpus->solver : std::vector<int>{});
    // The current session's swapchain images (made again after a lost session).
    std::optional<EyeTargets> eyes;
    eyes.emplace(vk.device, xr.eye(0), xr.eye(1));
    CommitWatch commits;  // before the service: its worker calls into it until the service is destroyed
    deform::ServiceOptions service_options;
    service_options.on_publish = commits.callback();
    service_options.worker_nice = o.solver_nice;  // frames first: the solver takes what the frame loop leaves
    service_options.worker_idle = o.solver_idle;
    if (cpus) service_options.worker_cpus = cpus->solver;
    deform::Service service(rest, std::move(service_options));
    ReviewInteraction interaction(service, *rest, placement, interaction_options);
    std::size_t next_method_change = 0;  // into o.method_changes
    bool commands_pending = false;       // a commit, undo or redo was issued and the service may still run it
    long held_frames = 0;                // frames a press has been held back (press_hold.hpp); 0: none held
    double hold_from = 0.0;              // the frame it has been held since
    bool trigger_was_taken = false;      // the grip or the menu panel had the triggers last frame
    std::size_t next_hold = 0;           // replay: into o.press_holds
    long recording_rate_hz = 0;          // the headset's display rate, whole Hz (0 before the first frame)
    std::int64_t recording_frames = 0;   // frames the loop has read input for
    double t = 0.0;  // the recording's time of this frame (seconds; the simulated runtime's script clock)
    // Whether the press held back since `from` goes through in this frame (t). Live: when the service is idle
    // (never waiting). Replay: at the end of the recorded hold that began at `from`, else at once (a
    // recording without holds: the loop of older versions waited there); it waits for the service then, as
    // the recorded loop found it idle.
    auto admit_press = [&](double from) {
      if (!o.press_holds) return service.idle();
      const double half_frame = 0.5 / double(std::max(1L, recording_rate_hz));
      const std::vector<PressHold>& holds = *o.press_holds;
      for (; next_hold < holds.size() && holds[next_hold].until < from - half_frame; ++next_hold) {
        if (holds[next_hold].admitted)  // the recorded press went through, this replay never held it
          std::fprintf(stderr,
                       "pushpull replay: warning: the press held from %.3f s to %.3f s in the recording was not "
                       "reproduced (the replay diverged before it)\n",
                       holds[next_hold].from, holds[next_hold].until);
      }
      const bool recorded = next_hold < holds.size() && std::abs(holds[next_hold].from - from) < half_frame;
      // A recorded hold that did not go through holds until the trigger is let go (or the session ends).
      if (recorded && (!holds[next_hold].admitted || holds[next_hold].until > t + half_frame)) return false;
      if (recorded) ++next_hold;
      service.wait_idle();
      return true;
    };
    // A hold that ends without its press going through (let go, session lost, review ended).
    auto end_hold = [&] {
      if (held_frames > 0) recorder.write_record("press held", t, {{"from", hold_from}, {"admitted", false}});
      held_frames = 0;
    };
    auto take_commits = [&] {
      app::take_commits(commits, recorder, t, o.on_commit, o.on_failed_commit, o.quiet);
    };
    TimedNotice notice;  // "nothing to undo", for a while by the hand and in the mirror's HUD
    std::size_t next_history_step = 0;  // replay: into o.history_steps
    auto ask_history_step = [&](HistoryStep step) {
      std::optional<bool> recorded;
      if (o.history_steps) {  // replay: sent when the recording sent it at this frame
        const double half_frame = 0.5 / double(std::max(1L, recording_rate_hz));
        const auto& steps = *o.history_steps;
        while (next_history_step < steps.size() && steps[next_history_step].first < t - half_frame)
          ++next_history_step;
        const char* name = step == HistoryStep::Undo ? "undo" : "redo";
        recorded = next_history_step < steps.size() && steps[next_history_step].first <= t + half_frame &&
                   steps[next_history_step].second == name;
        if (*recorded) ++next_history_step;
      }
      if (take_history_step(service, step, t, t, log, recorder, notice, !o.quiet, recorded))
        commands_pending = true;
    };
    auto history_text = [&] { return edit_counts_text(edit_counts(service)); };
    std::optional<xr::Input> input;  // per session, like the eyes
    input.emplace(xr.instance(), xr.handle(), xr.stage_space(), xr.enabled_extensions());
    FrameStats stats;
    SizeSteering sizes;
    bool stick_said = false;    // this drag's stick push was said to change nothing
    std::string profile_said;   // the interaction profile last said on stdout
    bool stick_pushed = false;  // the right stick was pushed (beyond half way) last frame
    const bool format_6 = o.behaviour_of_format >= 6;
    const bool format_7 = o.behaviour_of_format >= 7;
    const bool format_8 = o.behaviour_of_format >= 8;
    // A grip squeezed during a drag (a reviewer clenching the controller while pulling) or held through a
    // lost session grabs the model only once let go and squeezed again (format 8), per hand.
    std::array<bool, 2> grip_needs_release{false, false};
    bool trackpad_steps = false;  // the right hand's "thumbstick" is a trackpad (size_steering.hpp; format 7)
    GrabPlacement grab(placement, /*scale_on_floor=*/format_6);
    AnchorSchedule anchor_schedule(o.recorded_anchor);  // when the model moves in front of the reviewer
    ReviewMenu menu;
    WorldLabel hand_label(renderer, 0.02f, 600), menu_label(renderer, 0.03f, 1500);
    Eigen::Vector3d head_position(0.0, 1.6, 0.0), head_forward(0.0, 0.0, -1.0);  // stage; the last seen

    // The model moved on the stage (grip): what aims at it, draws it and frames it follows.
    auto place_model = [&](const StagePlacement& p) {
      interaction.set_placement(p);
      scene.set_placement(p);
      if (mirror) mirror->set_orbit_bounds(stage_bounds(rest->V, p));  // O(#V): only with a mirror
    };
    // A method change (headset panel, mirror key, or a replayed one) is a "method" record at this frame.
    auto change_method = [&](deform::Method method) {
      const deform::Method before = interaction.method();
      interaction.set_method(method);
      if (interaction.method() == before) return;
      recorder.write_method(t, interaction.method());
      log.write_method(interaction.method());
    };
    // Likewise a colour-map change is a "colour" record (the panel's are replayed through its input too).
    auto change_colour = [&](ReviewColour c) {
      if (c == scene.colour()) return;  // e.g. a replayed record, then the panel's choice it came from
      scene.set_colour(c);
      recorder.write_colour(t, c);
      log.write_colour(c);
    };
    std::size_t next_colour_change = 0;  // into o.colour_changes
    std::size_t next_size_change = 0;    // into o.size_changes
    std::size_t next_cancel = 0;         // into o.cancels
    // A pull longer than the whole model (a tracking jump at the release, a hand thrown): committed as asked,
    // and said, with the way back.
    // Its longest side, as the review prints the model's size (the diagonal let a 1.5 m pull of a 1 m cube
    // pass unsaid).
    const double model_size = model.bounds.isEmpty() ? 0.0 : model.bounds.sizes().maxCoeff();
    auto log_event = [&](const InteractionEvent& e) {
      if (e.kind == InteractionEvent::Kind::Committed) commits.expect_commit(e.request);
      log.write_interaction(e, life);
      recorder.write_interaction(t, e, interaction.handle_radius(), interaction.roi_radius());
      if (e.kind == InteractionEvent::Kind::Committed)
        if (const auto warning = long_pull_warning(e.d.norm(), model_size, life.scale()))
          std::fprintf(stderr, "pushpull review: warning: %s\n", warning->c_str());
    };

    // Ctrl-C or SIGTERM: the review ends as with Esc (the committed work is written); a second one ends it at
    // once.
    std::optional<InterruptRequests> interrupts;
    if (o.end_on_interrupt) interrupts.emplace();
    auto interrupted = [&] { return interrupts && interrupts->requested(); };
    // The mirror's X display gone: Xlib ends the process (the headset's session with it) once this returns.
    // (last_words is declared after everything they use: it goes first.)
    std::optional<renderer::MirrorWindow::LastWords> last_words;
    if (mirror)
      last_words.emplace(mirror->on_connection_lost([&] {
        std::fprintf(stderr,
                     "pushpull review: the mirror window's display is gone; ending the review (the "
                     "committed work is kept)\n");
        finish_review_on_lost_display(
            [&] {
              if (interaction.dragging())
                if (const auto e = interaction.cancel()) log_event(*e);
              end_hold();
              service.wait_idle();
              take_commits();
            },
            recorder, log, t, service, o.out, model);
      }));
    // The session was lost (headset unplugged, runtime restarted): the drag in progress is cancelled (the
    // model stays as it was before it); the committed work stays, and with --reconnect the review goes on
    // when the headset is back. Returns whether it is back.
    auto resume_after_loss = [&]() -> bool {
      std::printf("pushpull review: the OpenXR session was lost\n");
      end_hold();
      if (const auto e = interaction.cancel()) log_event(*e);
      log.write({{"event", "lost"}});
      recorder.write_record("lost", t);
      // As xr/sim's script event: a replay loses the session there too.
      recorder.write_event_input(t, "loss");
      if (!(o.reconnect_s > 0.0)) return false;
      std::printf("pushpull review: waiting up to %.0f s for the headset to come back\n", o.reconnect_s);
      std::fflush(stdout);
      renderer.wait_idle();  // the eye images go with the session
      eyes.reset();
      input.reset();
      if (interrupted() || !xr.recreate_after_loss(o.reconnect_s, interrupted)) {
        std::printf(
            "pushpull review: %s; ending the review\n",
            interrupted() ? "interrupted while waiting for the headset" : "the headset did not come back");
        return false;
      }
      eyes.emplace(vk.device, xr.eye(0), xr.eye(1));
      input.emplace(xr.instance(), xr.handle(), xr.stage_space(), xr.enabled_extensions());
      menu = ReviewMenu{};
      // A trigger still pulled when the headset is back must be let go before it presses: the live review
      // read no release across the loss and did not press, but its replay, whose runtime loses the session
      // through LOSS_PENDING, read the last frame's inputs as released and pressed again at once.
      interaction.require_release();
      if (format_8) grip_needs_release = {true, true};  // likewise a grip still squeezed
      log.write({{"event", "session recreated"}});
      recorder.write_record("resumed", t);
      std::printf("pushpull review: the headset is back; the review goes on\n");
      return true;
    };

    bool session_lost = false;                                   // a call failed with XR_ERROR_SESSION_LOST
    std::array<std::optional<HandSample>, 2> last_tracked_hand;  // hold_untracked's, per hand
    // An error that ended the loop early (a runtime or GPU failure): the committed work is still saved and
    // the recording ended, then the review fails with it.
    std::optional<std::string> failure;
    std::optional<Clock::time_point> interrupted_at;  // when the loop saw an interrupt
    // The mirror's image acquired in a frame that threw before presenting it: given up.
    auto abandon_mirror_frame = [&] {
      if (mirror) mirror->abandon();
    };
    // Whether the review asked to end (Esc, the window, Ctrl-C): otherwise an exit is the runtime's (the
    // reviewer quit from its menu), recorded as xr/sim's exit event so that a replay ends there too.
    bool asked_to_exit = false;
    std::optional<Clock::time_point> exit_asked_at;  // the first request
    auto ask_exit = [&] {
      asked_to_exit = true;
      if (!exit_asked_at) exit_asked_at = Clock::now();
      xr.request_exit();
    };
    while (!xr.exit_requested() || xr.lost() || session_lost) {
      if (interrupted() && !interrupted_at) {
        interrupted_at = Clock::now();
        std::printf("pushpull review: interrupted; ending the review (again to quit at once)\n");
        std::fflush(stdout);
        guarded(failure, ask_exit);
        if (session_lost || xr.lost() || failure) break;  // nothing to end gracefully
      }
      // A runtime that does not end the session within 3 s of the request (Ctrl-C, Esc, the window closed):
      // the review ends without it (the session is destroyed in any state), rather than a second Ctrl-C or a
      // kill losing the work.
      if (exit_asked_at && Clock::now() - *exit_asked_at > std::chrono::seconds(3)) {
        std::printf(
            "pushpull review: the OpenXR runtime did not end the session within 3 s of the request; "
            "ending without it\n");
        break;
      }
      if (session_lost || xr.lost()) {
        bool back = false;
        try {
          back = resume_after_loss();
        } catch (const std::exception& e) {  // making the session again failed: the review ends on it
          failure = std::string("the session could not be made again after it was lost: ") + e.what();
        }
        if (!back) break;
        session_lost = false;
        continue;
      }
      try {
        xr.poll_events();
        if (xr.exit_requested()) continue;  // ends the loop, or (lost) handled at its top
        if (!xr.running()) {
          // The headset is idle (standby, not yet ready): the supervisor's window still answers (close, Esc).
          if (mirror) {
            for (int key : mirror->poll())
              if (key == 256 /* GLFW_KEY_ESCAPE */) ask_exit();
            if (mirror->should_close()) ask_exit();
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
          continue;
        }
        const xr::FrameViews frame = xr.begin_frame();
        if (xr.lost()) continue;
        const auto start = Clock::now();
        const double start_cpu_ms = thread_cpu_ms();
        input->sync(frame.predicted_display_time);
        // The recording's clock counts frames: frame n at n / rate, exactly as xr/sim's virtual clock at that
        // (whole) rate places it, so a replay gives frame n the input the loop read at its frame n, whatever
        // the headset's timing (jitter, dropped frames) was.
        if (recording_rate_hz == 0) {
          // A runtime not yet synchronised may predict no period (0) or a meaningless one: the recording
          // then counts frames at 90 Hz (only its times depend on the rate, not what frame n reads).
          const XrDuration period = frame.predicted_display_period;
          const long rate = period > 0 ? std::lround(1e9 / double(period)) : 0;
          recording_rate_hz = rate >= 10 && rate <= 1000 ? rate : 90;
          recorder.write_record("clock", 0.0, {{"rate_hz", recording_rate_hz}});
        }
        t = double(std::llround(double(recording_frames++) * 1e9 / double(recording_rate_hz))) * 1e-9;
        if (o.on_frame) o.on_frame(t);
        {
          std::optional<XrPosef> head;
          if (frame.should_render) {
            // The head: between the eyes, looking between them (displays may be canted outwards, each eye
            // turned by a few degrees; on a display that is not, both eyes share the head's orientation).
            const XrPosef& l = frame.eyes[0].T_stage_eye;
            const XrPosef& r = frame.eyes[1].T_stage_eye;
            const Eigen::Quaterniond between =
                Eigen::Quaterniond(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z)
                    .slerp(0.5, Eigen::Quaterniond(r.orientation.w, r.orientation.x, r.orientation.y,
                                                   r.orientation.z));
            head = XrPosef{{float(between.x()), float(between.y()), float(between.z()), float(between.w())},
                           {(l.position.x + r.position.x) * 0.5f, (l.position.y + r.position.y) * 0.5f,
                            (l.position.z + r.position.z) * 0.5f}};
            head_position = Eigen::Vector3d(head->position.x, head->position.y, head->position.z);
            head_forward = between * Eigen::Vector3d(0.0, 0.0, -1.0);
          }
          const std::string profile = input->current_profile(xr::Hand::Right);
          // Which controllers the runtime bound (a profile without a grip or stick limits what a reviewer
          // can do, and buttons that do nothing are otherwise unexplained).
          const std::string bound =
              profile.empty() ? input->current_profile(xr::Hand::Left) : profile;  // a left hand alone
          if (bound.empty() && profile_said.empty() && t > 5.0 && !xr.lost() && xr.focused() && !o.quiet) {
            std::printf(
                "pushpull review: no controller is bound after 5 s: the review needs motion "
                "controllers (hand tracking alone is not supported); turn them on\n");
            profile_said = "none";
          }
          if (bound != profile_said && !bound.empty()) {
            profile_said = bound;
            if (!o.quiet)
              std::printf(
                  "pushpull review: controllers: %s%s\n", bound.c_str(),
                  bound == "/interaction_profiles/khr/simple_controller"
                      ? " (select: push/pull; left menu: undo, right menu: redo; no grip, sizes or panel)"
                      : "");
          }
          trackpad_steps = format_7 && profile == kTrackpadProfile;
          recorder.write_frame_input(t, head, {input->hand(xr::Hand::Left), input->hand(xr::Hand::Right)},
                                     profile);
          // The model in front of the reviewer, wherever they stand (head_anchor.hpp): once per review, at
          // the first frame whose head position is located (live; a headset tracked in orientation only never
          // is), or at the recorded frame (replay).
          if (!anchor_schedule.done()) {
            std::optional<Eigen::Vector3d> located;
            if (head && frame.position_valid) located = head_position;
            if (const auto anchor =
                    anchor_schedule.take(t, 0.5 / double(recording_rate_hz), located, head_forward)) {
              // A gesture begun before the head was located aimed at the model where it stood then.
              if (interaction.dragging())
                if (const auto e = interaction.cancel()) log_event(*e);
              const StagePlacement at_head = anchored(placement, *anchor);
              grab = GrabPlacement(at_head, /*scale_on_floor=*/format_6);
              place_model(at_head);
              nlohmann::json fields{{"x", anchor->x}, {"z", anchor->z}, {"yaw", anchor->yaw}};
              if (anchor->floor_y != 0.0) {
                fields["floor_y"] = anchor->floor_y;
                if (!o.quiet && !o.recorded_anchor)
                  std::printf(
                      "pushpull review: the head is %.2f m above the stage space's origin, not %.1f-%.1f "
                      "m: the runtime's stage is not at floor level; the model stands %.1f m below "
                      "the head\n",
                      head_position.y(), kFloorLevelHeadMin, kFloorLevelHeadMax, kAssumedEyeHeight);
              }
              recorder.write_record("anchor", t, fields);
            }
          }
        }
        // The stage space moves (the reviewer recentred the view): hand positions jump, and a drag spanning
        // the jump would push it into the model; it is cancelled, the model stays as before it.
        if (xr.take_space_change()) {
          recorder.write_event_input(t, "recenter");  // xr/sim raises it again in a replay
          if (interaction.dragging())
            if (const auto e = interaction.cancel()) log_event(*e);
        }
        // Focus lost mid-drag (a system menu, another app): the inputs read as released, which the gesture
        // would take as a release; the drag is cancelled instead, the model stays as before it.
        if (!xr.focused() && interaction.dragging())
          if (const auto e = interaction.cancel()) log_event(*e);
        std::array<HandSample, 2> hands{hold_untracked(input->hand(xr::Hand::Left), last_tracked_hand[0]),
                                        hold_untracked(input->hand(xr::Hand::Right), last_tracked_hand[1])};
        // Grip (between drags): grab and move the model; both grips also scale it.
        for (int h = 0; h < 2; ++h) {
          const bool squeezed = input->hand(xr::Hand(h)).grip > 0.5f;
          if (!squeezed)
            grip_needs_release[size_t(h)] = false;
          else if (interaction.dragging() && format_8)
            grip_needs_release[size_t(h)] = true;
        }
        if (!interaction.dragging()) {
          std::array<std::optional<GrabHand>, 2> grabbing;
          for (int h = 0; h < 2; ++h)
            if (input->hand(xr::Hand(h)).grip > 0.5f && hands[size_t(h)].tracked &&
                !grip_needs_release[size_t(h)])
              grabbing[size_t(h)] = GrabHand{hands[size_t(h)].origin_stage, heading(hands[size_t(h)])};
          const bool was_grabbing = grab.grabbing();
          if (grab.update(grabbing)) place_model(grab.placement());
          if (was_grabbing && !grab.grabbing()) {
            std::vector<double> T;
            for (int r = 0; r < 4; ++r)
              for (int c = 0; c < 4; ++c) T.push_back(grab.placement().T_stage_model(r, c));
            log.write(
                {{"event", "placement"}, {"T_stage_model", T}, {"relative_scale", grab.relative_scale()}});
            if (!o.quiet)
              std::printf("pushpull review: model moved (%.0f%% of life size)\n",
                          100.0 * grab.relative_scale());
          }
          if (grab.grabbing())
            for (auto& hand : hands) hand.trigger = 0.0f;  // no push/pull while holding the model
        }
        // The method and colour-map panel (menu button): opens in front of the reviewer; while open the right
        // stick chooses, the trigger applies, and nothing is pushed or pulled.
        // A trackpad's click on its rim steps the sizes instead (size_steering.hpp). Mid-drag: said, not
        // done.
        for (int h = 0; h < 2 && interaction.dragging(); ++h)
          if (input->hand(xr::Hand(h)).menu_pressed)
            announce(notice,
                     trackpad_steps && h == int(xr::Hand::Right) ? "sizes change between drags"
                                                                 : "the panel opens between drags",
                     t, !o.quiet);
        for (int h = 0; h < 2 && !interaction.dragging(); ++h) {
          const xr::HandInput& pressed = input->hand(xr::Hand(h));
          if (!pressed.menu_pressed) continue;
          if (trackpad_steps && h == int(xr::Hand::Right) && !menu.is_open()) {
            if (const auto step = trackpad_click_step(pressed.thumbstick.x, pressed.thumbstick.y)) {
              interaction.scale_sizes(step->handle, step->region);
              report_sizes(interaction, log, life, !o.quiet);
              break;
            }
          }
          menu.toggle(interaction.method());
          if (menu.is_open()) {  // 0.5 m along the gaze, centred on it, where it was opened (world-locked)
            menu_label.set_text(menu.lines(interaction.method(), scene.colour()), menu.selected_line());
            menu_label.place(head_position + 0.5 * head_forward -
                                 Eigen::Vector3d(0.0, 0.5 * double(menu_label.height()), 0.0),
                             head_position);
          }
          break;
        }
        if (menu.is_open()) {
          const xr::HandInput& right = input->hand(xr::Hand::Right);
          const MenuChoice choice = menu.update(right.thumbstick.y, right.trigger);
          if (choice.method && !o.fixed_method) change_method(*choice.method);
          if (choice.colour) change_colour(*choice.colour);
          for (auto& hand : hands) hand.trigger = 0.0f;
        }
        // A trigger the grip or the panel had stays theirs until it is let go: a reviewer who squeezes grip
        // and trigger together to carry the car, then lets go of the grip first, does not push or pull.
        const bool trigger_taken = grab.grabbing() || menu.is_open();
        if (trigger_was_taken && !trigger_taken && format_6) interaction.require_release();
        trigger_was_taken = trigger_taken;
        // A press while a commit, undo or redo is still being solved would hit the surface the reviewer no
        // longer sees: it is held back (the triggers read as released) until the service is idle, and the
        // frame goes on. The hold is recorded, so a replay holds the same press over the same frames.
        // The hold starts when a trigger goes down as a press (ReviewInteraction::would_press: the input alone
        // decides, so a replay starts it at the same frame) and lasts while the trigger stays pulled.
        {
          const bool pressing = held_frames > 0 ? interaction.trigger_held(hands)
                                                : commands_pending && interaction.would_press(hands);
          if (pressing) {
            if (held_frames == 0) hold_from = t;
            if (admit_press(hold_from)) {
              if (held_frames > 0) {
                recorder.write_record("press held", t, {{"from", hold_from}, {"admitted", true}});
                log.write({{"event", "press held"}, {"frames", held_frames}});
              }
              held_frames = 0;
              commands_pending = false;
              interaction.sync_committed(*service.latest());
            } else {
              ++held_frames;
              for (auto& hand : hands) hand.trigger = 0.0f;
            }
          } else {  // let go while held (if held): nothing was pressed
            end_hold();
          }
        }
        // Replay: the sizes a key set, before the gesture, as the desktop window set them.
        // (A recorded change applies at the frame within a quarter frame of its time.)
        const double due_until = t + 0.25 / double(recording_rate_hz);
        // Replay: a drag the recorded reviewer cancelled (Esc in the desktop window), before the gesture and
        // before the sizes (the window took Esc first when both came in one frame: a size key mid-drag is
        // refused and not recorded). Not dragging here where the recording was: the replay has diverged.
        apply_due(o.cancels, next_cancel, due_until, [&](double time) {
          if (!interaction.dragging()) {
            std::fprintf(
                stderr,
                "pushpull review: warning: the recording cancels a drag at %.3f s, where this replay "
                "has none in progress\n",
                time);
            return;
          }
          if (const auto e = interaction.cancel()) log_event(*e);
          recorder.write_record("cancel", t);
        });
        apply_due(o.size_changes, next_size_change, due_until, [&](const SizeChange& c) {
          interaction.set_sizes(c.handle_radius, c.roi_radius);
          recorder.write_sizes(t, interaction.handle_radius(), interaction.roi_radius());
        });
        // A trigger pulled while aiming beside the model grabs nothing: said, as the desktop window says a
        // click beside it (a reviewer pulled and saw nothing happen).
        const bool pressing = xr.focused() && interaction.would_press(hands);
        // Input is ours only while focused (unfocused, every input reads as released): no gestures then.
        for (const InteractionEvent& e :
             xr.focused() ? interaction.update(hands) : std::vector<InteractionEvent>{}) {
          if (e.kind == InteractionEvent::Kind::Committed) commands_pending = true;
          log_event(e);
          if (e.kind != InteractionEvent::Kind::Cancelled) input->haptic_pulse(xr::Hand(e.hand), 0.6f, 0.03);
        }
        if (interaction.dragging()) recorder.write_drag(t, interaction.current_d());
        if (pressing && !interaction.dragging())
          announce(notice, "the trigger pushes and pulls where the ray meets the model: aim at its surface",
                   t, !o.quiet);
        for (int h = 0; h < 2 && !interaction.dragging(); ++h) {
          const xr::HandInput& in = input->hand(xr::Hand(h));
          if (in.undo_pressed && grab.grabbing()) {  // undo while holding it: the session's first placement
            grab.reset();
            place_model(grab.placement());
            log.write({{"event", "placement reset"}});
          } else if (in.undo_pressed) {
            ask_history_step(HistoryStep::Undo);
          }
          if (in.redo_pressed) ask_history_step(HistoryStep::Redo);
        }
        for (int h = 0; h < 2 && interaction.dragging(); ++h) {
          const xr::HandInput& in = input->hand(xr::Hand(h));
          if (in.undo_pressed || in.redo_pressed)
            announce(notice, "undo and redo act between drags", t, !o.quiet);
        }
        // Replay: the method changes the recording made with a key, at the frames it made them.
        apply_due(o.method_changes, next_method_change, due_until,
                  [&](const auto& change) { change_method(deform::parse_method(change.second)); });
        // The mirror's keys, where a replay applies the method and colour changes they made.
        if (mirror) {
          for (int key : mirror->poll()) {
            if (key == 'C') change_colour(next_colour(scene.colour()));
            if (key == 'V') mirror->next_mode();
            if (key == 'M' && !o.fixed_method) {
              if (interaction.dragging())
                announce(notice, "the method changes between drags", t, !o.quiet);
              else
                change_method(next_method(interaction.method()));
            }
            if (key == 256 /* GLFW_KEY_ESCAPE */) ask_exit();
          }
          if (mirror->should_close()) ask_exit();
        }
        apply_due(o.colour_changes, next_colour_change, due_until, [&](const auto& change) {
          if (const auto c = parse_colour(change.second)) change_colour(*c);
        });
        // Right thumbstick between drags: the handle and region sizes (size_steering.hpp).
        {
          const XrVector2f stick = input->hand(xr::Hand::Right).thumbstick;
          sizes.frame(interaction, stick.x, stick.y, recording_frame_period_s(double(recording_rate_hz)),
                      !menu.is_open() && !trackpad_steps, log, life, !o.quiet);
          // Pushed from rest mid-drag: said once a drag (the drag keeps the sizes it grabbed with).
          const bool pushed = std::hypot(double(stick.x), double(stick.y)) > 0.5 && !trackpad_steps;
          if (!interaction.dragging()) {
            stick_said = false;
          } else if (pushed && !stick_pushed && !stick_said && !menu.is_open()) {
            announce(notice, "sizes change between drags", t, !o.quiet);
            stick_said = true;
          }
          stick_pushed = pushed;
        }
        // Replay: a frame that is kept shows the solver's settled state, not whichever preview timing left.
        if (o.settle_drawn_frames && frame.should_render && o.draw_frame && o.draw_frame(t))
          service.wait_idle();
        take_commits();
        const std::shared_ptr<const deform::Snapshot> snapshot = service.latest();
        const bool solving = interaction.dragging() || !snapshot->final;
        if (snapshot->region)
          stats.region_vertices = std::max(stats.region_vertices, snapshot->region->size());
        interaction.sync_committed(*snapshot);
        {
          const std::uint64_t generation = scene.generation();
          scene.update(snapshot, /*wait=*/o.settle_drawn_frames);
          if (scene.generation() != generation) stats.add_snapshot(scene.last_cpu_ms());
        }
        // The handle a press would grab, highlighted on the surface; |d| and the solver's state by the hand.
        {
          int h = interaction.dragging() ? interaction.drag_hand() : -1;
          for (int k : {1, 0})
            if (h < 0 && hands[size_t(k)].tracked && interaction.hovers()[size_t(k)]) h = k;
          // A notice ("nothing to undo") shows by a hand even when it aims at nothing.
          for (int k : {1, 0})
            if (h < 0 && hands[size_t(k)].tracked && !notice.text(t).empty()) h = k;
          static const std::vector<int> kNoVertices;
          scene.set_highlight(h >= 0 && !interaction.dragging() ? interaction.hover_handle(h) : kNoVertices);
          if (h >= 0 && hands[size_t(h)].tracked) {
            hand_label.set_text(readout_lines(interaction, *snapshot, life, held_frames > 0, notice.text(t)));
            hand_label.place(hands[size_t(h)].origin_stage + Eigen::Vector3d(0.0, 0.05, 0.0), head_position);
          } else {
            hand_label.hide();
          }
          if (menu.is_open())
            menu_label.set_text(menu.lines(interaction.method(), scene.colour()), menu.selected_line());
          else
            menu_label.hide();
        }
        // The eyes draw both labels where they stand; the mirror's own views draw the hand's clear of its
        // HUD.
        std::vector<renderer::Draw> draws = scene.draws();
        if (const auto d = menu_label.draw()) draws.push_back(*d);
        std::vector<renderer::Draw> eye_draws = draws;
        if (const auto d = hand_label.draw()) eye_draws.push_back(*d);
        if (frame.should_render) last_eyes = frame.eyes;
        // One loop frame, one submission: the eyes (when the runtime wants them and the frame is drawn) and
        // the mirror window share one frame in flight and one upload of the newest snapshot.
        std::vector<renderer::RenderPass> passes;
        std::array<renderer::View, 2> eye_views;
        renderer::RenderTargets eye_targets;
        bool rendered = false;
        if (frame.should_render && (!o.draw_frame || o.draw_frame(t))) {
          const uint32_t left = xr.eye(0).acquire();
          const uint32_t right = xr.eye(1).acquire();
          eye_views = {eye_view(frame.eyes[0]), eye_view(frame.eyes[1])};
          eye_targets = eyes->targets(left, right);
          renderer::FrameSettings eye_settings = scene.settings();
          // See-through display: the world is the background.
          if (xr.blend_mode() != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) eye_settings.clear_colour = {0, 0, 0, 0};
          passes.push_back({eye_views, eye_draws, eye_settings, &eye_targets, {}});
          rendered = true;
        }
        if (mirror) {
          const std::optional<renderer::RenderPass> pass = mirror->pass(
              last_eyes, draws,
              window_hud_lines(
                  interaction, *snapshot, life, colour_name(scene.colour()), mirror->mode_text(),
                  {o.fixed_method ? std::string("V view  C colour  M method  Esc end")
                                  : "V view  C colour  M method (next " +
                                        std::string(deform::method_name(next_method(interaction.method()))) +
                                        ")  Esc end"},
                  history_text(), notice.text(t)),
              scene.settings(/*legend=*/true), rendered ? &eye_targets : nullptr, xr.eye(0).transfer_source(),
              &hand_label);
          if (pass) {
            scene.set_legend_window(pass->targets->extent.width, pass->targets->extent.height);
            passes.push_back(*pass);
          }
        }
        if (!passes.empty()) renderer.render_frame(passes);
        xr.end_frame(frame, rendered);
        if (mirror) {
          mirror->present();
          mirror->set_title(window_title("pushpull review", interaction.method(), interaction.dragging(),
                                         *snapshot, life, colour_name(scene.colour()), mirror->mode_text(),
                                         history_text(), notice.text(t)));
        }
        stats.add_frame(solving, std::chrono::duration<double, std::milli>(Clock::now() - start).count(),
                        thread_cpu_ms() - start_cpu_ms);
      } catch (const xr::XrError& e) {
        guarded(failure, abandon_mirror_frame);
        if (e.result() == XR_ERROR_SESSION_LOST || e.result() == XR_ERROR_INSTANCE_LOST) {
          session_lost = true;
          continue;
        }
        if (!failure) failure = e.what();
        break;
      } catch (const std::exception& e) {
        guarded(failure, abandon_mirror_frame);
        if (!failure) failure = e.what();
        break;
      }
    }
    // The runtime ended the session (its exit, not ours, nor a loss): in the middle of a drag the frame that
    // saw it read the trigger released and the drag was cancelled; a replay without the exit at that frame
    // took the release as one and committed the drag. Recorded at the last frame's time.
    if (xr.exit_requested() && !asked_to_exit && !xr.lost() && !session_lost && !failure)
      recorder.write_event_input(t, "exit");
    // The end, also after a failure (review_end.hpp). A drag still in progress is cancelled (as the desktop
    // loop does): the model stays as it was before it.
    if (mirror && mirror->lost())
      std::printf("pushpull review: the mirror window was closed from outside; ending the review\n");
    if (failure)
      std::fprintf(stderr, "pushpull review: %s; ending the review (the committed work is kept)\n",
                   failure->c_str());
    guarded(failure, [&] {
      if (interaction.dragging())
        if (const auto e = interaction.cancel()) log_event(*e);
    });
    guarded(failure, end_hold);  // a press still held back when the review ended never went through
    guarded(failure, [&] { renderer.wait_idle(); });
    // A push/pull still solving: the work committed before it is written first (finish_review writes it again
    // with that one), for a runtime that kills its applications a few seconds after its own exit (SteamVR on
    // Linux) while a large region solves.
    // (Only a file replaced whole: a stream, /dev/stdout or a pipe, would get two models.)
    if (!o.out.empty() && !service.idle() && !deform::holds_descriptor(o.out) &&
        (std::filesystem::is_regular_file(o.out) || !std::filesystem::exists(o.out))) {
      try {
        write_review_model(o.out, model, service.current().entry.state->V,
                           /*say_warnings=*/false);
      } catch (const std::exception&) {  // said by finish_review's write, which fails the same way
      }
    }
    service.wait_idle();
    guarded(failure, take_commits);
    finish_review(failure, recorder, log, t, service, o.out, model, !o.quiet);
    if (validation) {
      // The runtime's own messages fail the run only on our simulated runtime, whose code is ours too; on
      // another runtime they are said (its vendor's to fix), and pushpull's own still fail it.
      const bool simulated = xr.runtime_name().find("pushpull") != std::string::npos;
      const uint32_t ours = validation->message_count(), runtime = validation->runtime_message_count();
      if (ours > 0 || (simulated && runtime > 0))
        throw CommandError("Vulkan validation reported " + std::to_string(ours + (simulated ? runtime : 0)) +
                           " message(s) (printed above)");
      if (runtime > 0)
        std::fprintf(
            stderr,
            "pushpull review: Vulkan validation: %u message(s) from inside the OpenXR runtime \"%s\"'s "
            "work (printed above, marked so); none from pushpull's own\n",
            runtime, xr.runtime_name().c_str());
    }
    if (mirror) std::printf("pushpull review: %s\n", mirror->summary().c_str());
    if (o.benchmark) stats.print();
  }
}

}  // namespace pushpull::app
