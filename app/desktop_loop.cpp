#include "desktop_loop.hpp"

#include "drag_notes.hpp"

#include "commands.hpp"
#include "commit_reports.hpp"
#include "frame_stats.hpp"
#include "hand_sample.hpp"
#include "history_steps.hpp"
#include "interrupt_requests.hpp"
#include "orbit_control.hpp"
#include "review_end.hpp"
#include "review_interaction.hpp"
#include "review_scene.hpp"
#include "session_recorder.hpp"
#include "size_steering.hpp"
#include "window_hud.hpp"
#include "world_label.hpp"

#include "pushpull/deform/service.hpp"
#include "pushpull/renderer/camera.hpp"
#include "pushpull/renderer/context.hpp"
#include "pushpull/renderer/mirror_window.hpp"
#include "pushpull/renderer/renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

namespace pushpull::app {
namespace {

Eigen::Vector3d to_eigen(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The ray through a window pixel: origin at the camera, direction into the scene (stage space).
std::pair<Eigen::Vector3d, Eigen::Vector3d> cursor_ray(const renderer::View& view,
                                                        const renderer::MirrorWindow::Pointer& p) {
  const glm::mat4 inverse = glm::inverse(view.projection * view.view);
  const float x = float(2.0 * p.x / std::max(1, p.window_width) - 1.0);
  const float y = float(2.0 * p.y / std::max(1, p.window_height) - 1.0);  // Vulkan clip: y down like the window
  glm::vec4 near = inverse * glm::vec4(x, y, 0.0f, 1.0f), far = inverse * glm::vec4(x, y, 1.0f, 1.0f);
  near /= near.w;
  far /= far.w;
  const glm::vec3 camera = glm::vec3(glm::inverse(view.view)[3]);
  return {to_eigen(camera), to_eigen(glm::normalize(glm::vec3(far) - glm::vec3(near)))};
}

// The point of the line p0 + s n closest to the ray o + t r (both directions unit); none where the ray is
// within 15 degrees of the line: a pixel there moves the point by 1 / sin^2 of that angle times its size
// (centimetres a pixel, metres a drag, and back and forth with the cursor's jitter).
std::optional<Eigen::Vector3d> closest_on_line(const Eigen::Vector3d& p0, const Eigen::Vector3d& n,
                                               const Eigen::Vector3d& o, const Eigen::Vector3d& r) {
  const Eigen::Vector3d w = p0 - o;
  const double b = n.dot(r), d = n.dot(w), e = r.dot(w), denom = 1.0 - b * b;
  constexpr double kSin15Squared = 0.0669872981;  // sin^2(15 deg)
  if (denom < kSin15Squared) return std::nullopt;
  return p0 + ((b * e - d) / denom) * n;
}

// The camera as a head pose in stage space (OpenXR's view convention: looking along -Z, +Y up).
std::optional<XrPosef> camera_pose(const renderer::View& view) {
  const glm::mat4 camera = glm::inverse(view.view);
  const glm::quat q = glm::quat_cast(glm::mat3(camera));
  XrPosef pose;
  pose.position = {camera[3].x, camera[3].y, camera[3].z};
  pose.orientation = {q.x, q.y, q.z, q.w};
  return pose;
}

// The profile desktop recordings name: it has a trigger value and A/B buttons for the pointer's undo/redo.
constexpr const char* kDesktopProfile = "/interaction_profiles/oculus/touch_controller";

}  // namespace

void run_desktop(const ReviewCommandOptions& given, const ReviewSetup& setup) {
  ReviewCommandOptions o = given;  // the samples may change (below); the recording's header says which
  renderer::ContextOptions context_options;
  try {
    context_options.instance_extensions = renderer::MirrorWindow::required_instance_extensions();
  } catch (const std::exception& e) {
    throw CommandError(std::string("desktop mode: ") + e.what());
  }
  context_options.swapchain = true;
  context_options.validation = o.validation;
  renderer::Context context = renderer::Context::create(context_options);
  if (!o.samples_given && context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU && o.samples > 1) {
    if (!o.quiet)
      std::printf(
          "pushpull review: %s renders on the CPU: no MSAA in the desktop window (--samples %d for it)\n",
          context.properties().deviceName, o.samples);
    o.samples = 1;
  }
  EventLog log(o.events, !o.quiet);
  log.write_start(o, setup, "desktop");
  SessionRecorder recorder(o.record.empty() ? default_recording_path() : o.record, !o.record.empty());
  {
    RecordingContext recording;
    recording.runtime = "desktop";
    recording.view_configuration = "desktop window";
    recording.eye_width = o.mirror_size[0];
    recording.eye_height = o.mirror_size[1];
    recorder.write_header(o, setup, recording);
  }
  if (recorder.recording()) std::printf("pushpull review: recording the session to %s\n", recorder.path().c_str());
  const LifeSize& life = setup.life;
  {
    renderer::RendererOptions renderer_options;
    renderer_options.samples = VkSampleCountFlagBits(o.samples);
    renderer::Renderer renderer(context, renderer_options);
    renderer::MirrorWindow window(context, uint32_t(o.mirror_size[0]), uint32_t(o.mirror_size[1]),
                                  "pushpull review (desktop)");
    ReviewScene scene(renderer, setup.model, setup.placement, setup.colour, life.scale());
    CommitWatch commits;  // before the service: its worker calls into it until the service is destroyed
    deform::ServiceOptions service_options;
    service_options.on_publish = commits.callback();
    deform::Service service(setup.rest, std::move(service_options));
    ReviewInteraction interaction(service, *setup.rest, setup.placement, setup.interaction);
    // The recording's clock: frame n at n / 90 s (xr/sim's virtual clock at 90 Hz), so a replay on the simulated
    // runtime sees each recorded frame at its own frame.
    constexpr double kRecordingRate = 90.0;
    std::int64_t loop_frames = 0;
    double t = 0.0;
    recorder.write_record("clock", 0.0, {{"rate_hz", kRecordingRate}});
    Eigen::Vector3d hand_origin = Eigen::Vector3d::Zero(), hand_direction(0, 0, -1);
    Eigen::Vector3d press_origin = Eigen::Vector3d::Zero(), press_direction(0, 0, -1);
    // A drag released off the window pulls metres: committed as asked, and said, as in the headset.
    const double longest_side = setup.model.bounds.isEmpty() ? 0.0 : setup.model.bounds.sizes().maxCoeff();
    auto record_interaction = [&](const InteractionEvent& e) {
      if (e.kind == InteractionEvent::Kind::Committed) commits.expect_commit(e.request);
      log.write_interaction(e, life);
      recorder.write_interaction(t, e, interaction.handle_radius(), interaction.roi_radius());
      if (e.kind == InteractionEvent::Kind::Committed && !o.quiet)
        if (const auto warning = long_pull_warning(e.d.norm(), longest_side, life.scale()))
          std::fprintf(stderr, "pushpull review: warning: %s\n", warning->c_str());
    };
    auto take_commits = [&] {
      app::take_commits(commits, recorder, t, o.on_commit, o.on_failed_commit, o.quiet);
    };
    // "nothing to undo", for a while in the HUD and the readout, on the wall clock (t, the recording's, runs
    // at 90 frames a second whatever the window's frame rate).
    TimedNotice notice;
    const auto start = std::chrono::steady_clock::now();
    auto now = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    auto history_text = [&] { return edit_counts_text(edit_counts(service)); };
    // A key that does nothing now (mid-drag) says so: stdout, the HUD and the readout.
    auto say = [&](const char* text) { announce(notice, text, now(), !o.quiet); };
    auto ask_history_step = [&](HistoryStep step) {
      (void)take_history_step(service, step, t, now(), log, recorder, notice, !o.quiet);
    };

    // Orbit around the model's box on the stage, from the reviewer's side.
    const renderer::Bounds bounds = stage_bounds(setup.rest->V, setup.placement);
    WorldLabel cursor_label(renderer, 0.02f, 600);  // line height 0.02, scaled per frame
    WorldLabel hud(renderer, 0.02f, 1200);          // the window's top-left corner
    renderer::OrbitCamera start_view;
    start_view.azimuth_deg = 30.0f;
    start_view.elevation_deg = 25.0f;
    renderer::OrbitCamera orbit = start_view;
    renderer::MirrorWindow::Pointer last{};
    long held_frames = 0;  // frames the left button's press has been held back while the service solves
    // U and R presses not yet acted on, in order: each is a button press of the recorded controller, one a
    // frame, with a released frame between two of the same button (a replay reads two pressed frames in a
    // row as one press). Several presses within one frame (a slow renderer, a quick double tap) all act.
    std::deque<HistoryStep> queued_steps;
    int deferred_method_steps = 0;   // M presses that came with a release not yet shown (see below)
    bool said_along_normal = false;  // this drag's Shift pull was held for a view along the normal
    std::optional<HistoryStep> stepped_last_frame;
    bool dragging = false;
    bool end_after_release = false;  // Esc pressed as the button went up: end once the release committed
    Eigen::Vector3d p0_stage = Eigen::Vector3d::Zero(), normal_stage = Eigen::Vector3d::UnitY();
    Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();
    std::string title;
    int frames = 0;
    // An error that ended the loop early (a lost GPU device, a window system failure): the committed work is
    // still saved and the recording ended, then the review fails with it.
    std::optional<std::string> failure;
    // Ctrl-C or SIGTERM: the review ends as with Esc (the committed work is written); a second one ends it at
    // once.
    const InterruptRequests interrupts;
    // (last_words is declared after everything they use: it goes first.)
    const auto last_words = window.on_connection_lost([&] {
      finish_review_on_lost_display(
          [&] {
            if (const auto e = interaction.cancel()) record_interaction(*e);
            service.wait_idle();
            take_commits();
          },
          recorder, log, t, service, o.out, setup.model);
    });
    FrameStats stats;  // --benchmark
    stats.span = "window events .. present, CPU";
    while (!window.should_close() && (o.frames <= 0 || frames < o.frames)) {
      const auto frame_start = std::chrono::steady_clock::now();
      const double frame_start_cpu = thread_cpu_ms();
      if (interrupts.requested()) {
        std::printf("pushpull review: interrupted; ending the review (again to quit at once)\n");
        break;
      }
      if (end_after_release && !interaction.dragging()) break;  // Esc came with the release: now committed
      try {
        window.poll_events();
        if (window.lost()) break;  // its pointer and size would be garbage this frame
        t = double(std::llround(double(loop_frames++) * 1e9 / kRecordingRate)) *
            1e-9;  // as xr/sim's script_time
        bool quit = false;
        int colour_steps = 0, method_steps = 0;  // C and M presses this frame: each steps once
        for (int key : window.take_key_presses()) {
          // Back to the first view (not mid-drag: the drag's plane would jump with the camera).
          if ((key == 'F' || key == 268 /* GLFW_KEY_HOME */) && !interaction.dragging()) orbit = start_view;
          // [ ] shrink / grow the handle, - = the region, kSizeStep a press, at once; a "sizes" record, which
          // a replay sets again at this frame. Not mid-drag (the drag keeps the sizes it grabbed with).
          double handle_factor = 1.0, region_factor = 1.0;
          if (key == 91 /* GLFW_KEY_LEFT_BRACKET */) handle_factor = 1.0 / kSizeStep;
          if (key == 93 /* GLFW_KEY_RIGHT_BRACKET */) handle_factor = kSizeStep;
          if (key == 45 /* GLFW_KEY_MINUS */) region_factor = 1.0 / kSizeStep;
          if (key == 61 /* GLFW_KEY_EQUAL */) region_factor = kSizeStep;
          if (handle_factor != 1.0 || region_factor != 1.0) {
            if (interaction.dragging()) {
              say("sizes change between drags");
            } else {
              interaction.scale_sizes(handle_factor, region_factor);
              recorder.write_sizes(t, interaction.handle_radius(), interaction.roi_radius());
              report_sizes(interaction, log, life, !o.quiet);
            }
          }
          // Esc mid-drag cancels the drag (the model stays as before it; a "cancel" record, which a replay
          // applies at this frame); between drags it ends the review. (A first-time user pressed Esc to drop
          // a pull and lost the session.)
          // With the button already up (its release shown this frame or queued), the release commits first
          // and the review ends after this frame (ending at once cancelled the pull just released).
          if (key == 256 /* GLFW_KEY_ESCAPE */) {
            if (interaction.dragging() && window.pointer().left && !window.pointer().left_release_queued) {
              if (const auto e = interaction.cancel()) record_interaction(*e);
              recorder.write_record("cancel", t);
              say("push/pull cancelled: the model is as before it (Esc again ends the review)");
            } else if (interaction.dragging()) {
              end_after_release = true;
            } else {
              quit = true;
            }
          }
          if (key == 'U' || key == 'R') {
            // Mid-drag: refused, unless the button is already up (its release shown within two frames ends
            // the drag first; the undo then steps back over it).
            if (interaction.dragging() && window.pointer().left && !window.pointer().left_release_queued)
              say("undo and redo act between drags");
            else
              queued_steps.push_back(key == 'U' ? HistoryStep::Undo : HistoryStep::Redo);
          }
          colour_steps += key == 'C';
          method_steps += key == 'M';
        }
        if (quit) break;
        const auto frame = window.acquire();
        const VkExtent2D extent = window.extent();
        const float aspect = float(std::max(1u, extent.width)) / float(std::max(1u, extent.height));
        const renderer::MirrorWindow::Pointer p = window.pointer();
        // The wheel zooms towards the surface point under the cursor (it stays under the cursor), not the
        // model box's centre, which may lie behind the surface (a bonnet's): zoomed in, the surface was gone.
        std::optional<Eigen::Vector3d> zoom_towards;
        if (p.scroll > 0.0 && !interaction.dragging()) {
          const auto [zoom_origin, zoom_direction] =
              cursor_ray(renderer::frame_bounds(bounds, orbit, aspect), p);
          if (const auto hit = interaction.hit(zoom_origin, zoom_direction))
            zoom_towards = setup.placement.to_stage_point(hit->point);
        }
        const float scale_before = orbit.distance_scale;
        // The wheel mid-drag moved the cursor's ray and with it the pull (92 to 186 mm with the mouse still):
        // zoom acts between drags, as undo and the sizes do. (Turning stays: along the normal it is how a
        // pull is aimed.)
        renderer::MirrorWindow::Pointer pointer = p;
        if (interaction.dragging() && pointer.scroll != 0.0) {
          pointer.scroll = 0.0;
          say("zoom acts between drags");
        }
        orbit_with_pointer(orbit, pointer, last, p.right && last.right);
        if (zoom_towards) {
          const glm::vec3 target = bounds.centre() + orbit.target_offset;
          const float kept = orbit.distance_scale / scale_before;  // the distance's ratio, at most 1
          orbit.target_offset +=
              (1.0f - kept) *
              (glm::vec3(float(zoom_towards->x()), float(zoom_towards->y()), float(zoom_towards->z())) -
               target);
        } else if (p.scroll < 0.0 && orbit.distance_scale > scale_before) {  // out: back towards the centre
          orbit.target_offset *= scale_before / orbit.distance_scale;
        }
        const renderer::View view = renderer::frame_bounds(bounds, orbit, aspect);
        const auto [origin, direction] = cursor_ray(view, p);
        // The mouse as a controller: outside a drag the cursor ray; during a drag the ray of the press moved
        // by p1 - p0 (the headset gesture's d is the hand's travel). It goes through the float aim pose the
        // recording keeps, and through the same gesture as a headset hand, so a replay of the recording on
        // the simulated runtime reproduces p0, d and every commit bit for bit (the press below, the drag
        // after it).
        //
        // As in the headset loop: a press hits the committed surface, never one a pending commit, undo or
        // redo replaces; while one is solving the press is held back (the trigger reads as released, and the
        // window keeps drawing) and goes through, where the cursor then is, once the service is idle. The
        // recording shows the trigger pressed from that frame, where a replay finds the service idle too.
        if (!p.left) held_frames = 0;
        bool press = false;  // the trigger goes down this frame
        if (p.left && (!last.left || held_frames > 0) && !interaction.dragging()) {
          if (!service.idle()) {
            ++held_frames;
          } else {
            if (held_frames > 0) log.write({{"event", "press held"}, {"frames", held_frames}});
            held_frames = 0;
            interaction.sync_committed(*service.latest());
            press = true;
          }
        }
        if (press) {
          if (const auto hit = interaction.hit(origin, direction)) {
            p0_stage = setup.placement.to_stage_point(hit->point);
            const Eigen::Matrix3d A = setup.placement.T_stage_model.topLeftCorner<3, 3>();
            normal_stage = (A * interaction.face_normal(hit->face)).normalized();
            plane_normal = (p0_stage - origin).normalized();  // the view plane through p0
            press_origin = origin;
            press_direction = direction;
            said_along_normal = false;
          } else {
            // A press beside the model grabs nothing; a first-time user expected it to turn the view.
            say("the left button pushes and pulls the model's surface; the right button turns the view");
          }
        }
        if (interaction.dragging() && p.left) {
          Eigen::Vector3d p1 = p0_stage;
          if (p.shift) {
            if (const auto on_normal = closest_on_line(p0_stage, normal_stage, origin, direction)) {
              p1 = *on_normal;
            } else {  // looking along the normal: the pull stays where it was
              p1 = p0_stage + (hand_origin - press_origin);
              if (!said_along_normal) say("looking along the normal: turn the view to pull along it");
              said_along_normal = true;
            }
          } else if (std::abs(plane_normal.dot(direction)) > 1e-9) {
            p1 = origin + (plane_normal.dot(p0_stage - origin) / plane_normal.dot(direction)) * direction;
          }
          hand_origin = press_origin + (p1 - p0_stage);
          hand_direction = press_direction;
        } else if (!interaction.dragging()) {
          hand_origin = origin, hand_direction = direction;
        }
        // Released this frame: the hand stays where the drag left it (the gesture's release reads d there).
        // Recorded as a headset frame would be: the camera as the head, the pointer as the right controller
        // (its trigger the left button, its A and B buttons undo and redo); C and the size keys are "colour"
        // and "sizes" records.
        std::array<xr::HandInput, 2> hands_in;
        hands_in[1].T_stage_aim = pointer_pose(hand_origin, hand_direction);
        hands_in[1].trigger = p.left && held_frames == 0 ? 1.0f : 0.0f;
        std::optional<HistoryStep> step_now;
        // Not while the button is down outside a drag (a press may start one this frame and swallow the
        // step).
        if (!interaction.dragging() && !p.left && !queued_steps.empty() &&
            queued_steps.front() != stepped_last_frame) {
          step_now = queued_steps.front();
          queued_steps.pop_front();
        }
        stepped_last_frame = step_now;
        hands_in[1].undo_pressed = step_now == HistoryStep::Undo;
        hands_in[1].redo_pressed = step_now == HistoryStep::Redo;
        recorder.write_frame_input(t, camera_pose(view), hands_in, kDesktopProfile);
        for (const InteractionEvent& e :
             interaction.update({hand_sample(hands_in[0]), hand_sample(hands_in[1])}))
          record_interaction(e);
        if (interaction.dragging()) recorder.write_drag(t, interaction.current_d());
        dragging = interaction.dragging();
        // A drag begun first: undoing it next would surprise (not when its release is already queued: the
        // key came with the release).
        if (dragging && !queued_steps.empty() && !p.left_release_queued) {
          say("undo and redo act between drags");
          queued_steps.clear();
        }
        if (!dragging) {  // in the headset loop's order: after the gesture
          for (const auto& [pressed, step] : {std::pair{hands_in[1].undo_pressed, HistoryStep::Undo},
                                              std::pair{hands_in[1].redo_pressed, HistoryStep::Redo}})
            if (pressed) ask_history_step(step);
        }
        if (colour_steps > 0) {  // a "colour" record, which a replay applies at this frame
          ReviewColour colour = scene.colour();
          for (int i = 0; i < colour_steps; ++i) colour = next_colour(colour);
          scene.set_colour(colour);
          recorder.write_colour(t, scene.colour());
          log.write_colour(scene.colour());
        }
        scene.set_highlight(interaction.hover_handle(1));
        // M pressed as the button went up (its release still queued): applied once the drag has ended.
        if (method_steps > 0 && dragging && p.left_release_queued) {
          deferred_method_steps += method_steps;
          method_steps = 0;
        }
        if (!dragging) method_steps += std::exchange(deferred_method_steps, 0);
        if (method_steps > 0 && dragging && !o.fixed_method) say("the method changes between drags");
        if (method_steps > 0 && !dragging && !o.fixed_method) {
          deform::Method next = interaction.method();
          for (int i = 0; i < method_steps; ++i) next = next_method(next);
          interaction.set_method(next);
          recorder.write_method(t, interaction.method());
          log.write_method(interaction.method());
        }
        last = p;
        take_commits();

        const std::shared_ptr<const deform::Snapshot> snapshot = service.latest();
        const bool solving = interaction.dragging() || !snapshot->final;
        if (snapshot->region)
          stats.region_vertices = std::max(stats.region_vertices, snapshot->region->size());
        interaction.sync_committed(*snapshot);
        {
          const std::uint64_t generation = scene.generation();
          scene.update(snapshot);
          if (scene.generation() != generation) stats.add_snapshot(scene.last_cpu_ms());
        }
        // The readout by the cursor (where the press is, or where it would grab), the same size on screen at
        // any camera distance: a line about 3.5% of the view's height.
        std::vector<renderer::Draw> draws = scene.draws();
        {
          // M names the method it steps to: eight methods in a cycle are otherwise a guess.
          const std::string m_key =
              o.fixed_method ? "M method"
                             : "M method (next " +
                                   std::string(deform::method_name(next_method(interaction.method()))) + ")";
          hud.set_text(window_hud_lines(
              interaction, *snapshot, life, colour_name(scene.colour()), "",
              {"left drag: push/pull (Shift: along the normal)  right drag: turn  wheel: zoom",
               "[ ] handle  - = region  U undo  R redo  C colour  " + m_key + "  F first view  " +
                   (interaction.dragging() ? "Esc cancel" : "Esc end")},
              history_text(), notice.text(now())));
          const auto& hover = interaction.hovers()[1];
          const Eigen::Vector3d camera = to_eigen(glm::vec3(glm::inverse(view.view)[3]));
          std::optional<Eigen::Vector3d> anchor;
          if (interaction.dragging())
            anchor = setup.placement.to_stage_point(setup.placement.to_model_point(p0_stage) +
                                                    interaction.current_d());
          else if (hover)
            anchor = setup.placement.to_stage_point(hover->point);
          if (anchor) {
            const double distance = (camera - *anchor).norm();
            // projection[1][1] = -1 / tan(fov_y / 2) (Vulkan's clip y points down).
            const double tan_half_fov = 1.0 / std::max(1e-6, std::abs(double(view.projection[1][1])));
            const double line = 0.035 * 2.0 * distance * tan_half_fov;
            cursor_label.set_text(
                readout_lines(interaction, *snapshot, life, held_frames > 0, notice.text(now())));
            // Beside the point as a tooltip, not over the surface it edits: a line up and to its right, or
            // to its left in the right part of the window.
            const glm::mat4 camera_to_stage = glm::inverse(view.view);
            const Eigen::Vector3d right = to_eigen(glm::vec3(camera_to_stage[0])).normalized();
            const Eigen::Vector3d up = to_eigen(glm::vec3(camera_to_stage[1])).normalized();
            const glm::vec4 clip =
                view.projection * view.view *
                glm::vec4(float(anchor->x()), float(anchor->y()), float(anchor->z()), 1.0f);
            const double side = clip.w > 0.0f && clip.x / clip.w > 0.4f ? -1.0 : 1.0;
            const double half_width = 0.5 * double(cursor_label.width()) * line / 0.02;
            Eigen::Vector3d at = *anchor + side * (half_width + line) * right + line * up;
            // Inside the window and below the HUD: moved back in by what sticks out (clip y points down).
            if (clip.w > 0.0f) {
              const double depth = double(clip.w);  // the view depth of the anchor (perspective: clip w)
              const double x_per_m = 1.0 / (depth * tan_half_fov * double(aspect));  // NDC per metre
              const double y_per_m = 1.0 / (depth * tan_half_fov);
              const double cx = double(clip.x / clip.w) + (at - *anchor).dot(right) * x_per_m;
              const double bottom = double(clip.y / clip.w) - (at - *anchor).dot(up) * y_per_m;
              const double top = bottom - double(cursor_label.height()) * line / 0.02 * y_per_m;
              const double half = half_width * x_per_m;
              const double hud_bottom = -1.0 + 2.0 * (double(hud.height()) / 0.02 + 1.0) * 0.03;
              double dx = 0.0, dy = 0.0;
              if (cx + half > 0.98) dx = 0.98 - (cx + half);
              if (cx + dx - half < -0.98) dx = -0.98 - (cx - half);
              if (top < hud_bottom) dy = hud_bottom - top;
              if (bottom + dy > 0.98) dy = 0.98 - bottom;
              at += dx / x_per_m * right - dy / y_per_m * up;
            }
            cursor_label.place_on_image_plane(at, right, up, line / 0.02);
            if (const auto d = cursor_label.draw()) draws.push_back(*d);
          }
          hud.place_top_left(view, 0.03);
          if (const auto d = hud.draw()) draws.push_back(*d);
        }
        if (frame) {
          scene.set_legend_window(extent.width, extent.height);
          renderer.render(std::span(&view, 1), draws, scene.settings(/*legend=*/true), frame->targets,
                          frame->sync);
          window.present(*frame);
          ++frames;
        }
        const std::string text =
            window_title("pushpull review (desktop)", interaction.method(), dragging, *snapshot, life,
                         colour_name(scene.colour()), "", history_text(), notice.text(now()));
        if (title != text) window.set_title(title = text);
        if (frame)
          stats.add_frame(
              solving,
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start)
                  .count(),
              thread_cpu_ms() - frame_start_cpu);
      } catch (const std::exception& e) {
        failure = e.what();
        std::fprintf(stderr, "pushpull review: %s; ending the review (the committed work is kept)\n",
                     e.what());
        break;
      }
    }
    if (window.lost())
      std::printf("pushpull review: the window was closed from outside; ending the review as with Esc\n");
    // The end, also after a failure (review_end.hpp).
    guarded(failure, [&] {
      if (const auto e = interaction.cancel()) record_interaction(*e);
    });
    guarded(failure, [&] { renderer.wait_idle(); });
    service.wait_idle();
    guarded(failure, take_commits);
    std::printf("pushpull review: desktop window presented %d frames\n", frames);
    if (o.benchmark) stats.print();
    finish_review(failure, recorder, log, t, service, o.out, setup.model, /*print_out=*/true);
  }
  if (o.validation && context.validation_message_count() > 0)
    throw CommandError("Vulkan validation reported " + std::to_string(context.validation_message_count()) +
                       " message(s) (printed above)");
}

}  // namespace pushpull::app
