// `pushpull review`: push and pull a model in an OpenXR headset (review_loop.hpp).
#include "commands.hpp"
#include "messages_off_stdout.hpp"
#include "method_check.hpp"
#include "number_checks.hpp"
#include "review_loop.hpp"
#include "solver_cpus.hpp"

#include "pushpull/deform/cpu_affinity.hpp"
#include "pushpull/deform/file_output.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushpull::app {

void add_review_command(CLI::App& root) {
  auto o = std::make_shared<ReviewCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "review",
      "Review a model in an OpenXR headset at life size: "
      "aim at the surface, hold the trigger, drag, release.\n"
      "The model stands on the floor in front of where you stand when the session starts; the deformation "
      "runs "
      "off the frame loop.\n"
      "Controls: trigger = push/pull; "
      "undo = X/A (touch, hp reverb g2, vive cosmos), A (index), left menu (simple, vive, motion, odyssey);\n"
      "redo = Y/B (touch, g2, cosmos), B (index), right menu (simple, vive, motion, odyssey); "
      "menu (touch, g2, cosmos) / thumbstick or trackpad-centre click = the method and colour-map panel;\n"
      "grip = grab and move the model "
      "(both grips: scale, on the floor; undo while gripping: back to the session's first placement);\n"
      "right thumbstick between drags: handle radius (up/down) and region (left/right); vive: a click on "
      "the\n"
      "right trackpad's rim steps them (x1.25 a click).\n"
      "It ends with Esc in the mirror or desktop window (in the desktop window Esc during a drag cancels the "
      "drag), the runtime's exit, or Ctrl-C (the committed work "
      "is "
      "written to --out; a second Ctrl-C quits at once).\n"
      "Without a headset: "
      "XR_RUNTIME_JSON=build/xr/sim/pushpull_xr_sim.json runs it on the simulated runtime.");
  cmd->add_option("model", o->model, "Model file: .gltf .glb .drc .off .obj .ply")->required();
  cmd->add_option("--method", o->method,
                  "Deformation method (asan, arap-s, arap-sr, arap-m, arap-n, sr-arap, arap-h, arap-sr-h)")
      ->capture_default_str()
      ->check(method_name());
  cmd->add_option("--mu", o->mu, "ASAN stiffness ratio")->capture_default_str()->check(finite_above(1.0));
  cmd->add_option(
         "--handle-radius", o->handle_radius_m,
         "Handle: the surface within this distance of the hit point, along the surface (metres at life size)")
      ->capture_default_str()
      ->check(finite_above(0.0));
  cmd->add_option("--roi-radius", o->roi_radius_m,
                  "Region grown this far from the handle along the surface (metres at life size)")
      ->capture_default_str()
      ->check(finite_above(0.0));
  CLI::Option* up = cmd->add_option("--up", o->up, "The model's up axis X Y Z (default 0 1 0, glTF)")
                        ->expected(3)
                        ->check(finite_number());
  cmd->add_option("--front", o->front,
                  "The model's front axis X Y Z, turned towards you (default 0 0 1, glTF)")
      ->expected(3)
      ->check(finite_number());
  cmd->add_option("--distance", o->distance_m, "Gap between you and the model's nearest point (metres)")
      ->capture_default_str()
      ->check(finite_above(0.0, false));
  cmd->add_option("--eye-size", o->eye_size, "Per-eye image size W H (default: the runtime's recommendation)")
      ->expected(2)
      ->check(whole_number_in(16, 16384));
  CLI::Option* samples =
      cmd->add_option("--samples", o->samples,
                      "MSAA samples (desktop mode on a CPU renderer such as lavapipe: 1 unless given)")
          ->check(CLI::IsMember({1, 2, 4, 8}))
          ->capture_default_str();
  cmd->add_option("--color", o->colour, "Colour map at start (the headset's panel and the C key switch it)")
      ->check(CLI::IsMember({"material", "displacement", "curvature-sign"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Write the committed model on exit (.glb, .off, .obj, .ply)");
  cmd->add_option(
      "--events", o->events,
      "Write the session's events (press, commit, cancel, undo, redo, lost) as JSON Lines, with p0 and "
      "d in model units");
  cmd->add_option(
      "--record", o->record,
      "Record the session (header, input by OpenXR path, press/drag/release/commit with result hashes) "
      "as JSON Lines for `pushpull replay` (default: out/recordings/review-<UTC time>.jsonl)");
  cmd->add_flag(
      "--mirror", o->mirror,
      "Open the supervisor's mirror window (keys: V view: headset eye / smoothed first person / free orbit, "
      "C "
      "colour map, M method of the next drag, Esc end the session; a HUD and the title show method, |d|, "
      "iterations and the solver's state)");
  cmd->add_option("--mirror-size", o->mirror_size, "Mirror (or desktop) window size W H")
      ->expected(2)
      ->check(whole_number_in(16, 16384));
  cmd->add_flag(
      "--validation", o->validation,
      "Enable VK_LAYER_KHRONOS_validation on the runtime's Vulkan instance; fail on any message (the "
      "OpenXR core validation layer: XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation)");
  cmd->add_flag(
      "--desktop", o->desktop,
      "No headset: the window is the workspace (also when no OpenXR runtime or headset is found). Right "
      "drag turns, scroll zooms, left drag on the surface pushes/pulls (Shift: along the normal); U undo, R "
      "redo, C colour map, M method, [ ] handle size, - = region size, F or Home the first view, Esc cancels "
      "a drag in progress, else ends the review");
  cmd->add_option("--frames", o->frames, "Desktop mode: stop after N frames (0: when the window closes)");
  cmd->add_flag("--benchmark", o->benchmark, "Print the frame time, idle versus with the solver running");
  cmd->add_option(
         "--reconnect", o->reconnect_s,
         "After the OpenXR session is lost, wait this many seconds for the headset to come back and go on "
         "(0: end the review)")
      ->capture_default_str()
      ->check(finite_in(0.0, 86400.0));
  cmd->add_option("--headset-wait", o->headset_wait_s,
                  "At the start, wait this many seconds for a runtime's headset that has not connected yet "
                  "(streaming runtimes: WiVRn, ALVR) before opening the desktop window instead")
      ->check(finite_in(0.0, 86400.0))
      ->capture_default_str();
  cmd->add_option_function<std::string>(
         "--solver-priority",
         [o](const std::string& value) {
           o->solver_idle = value == "idle";
           if (!o->solver_idle) o->solver_nice = std::stoi(value);
         },
         "Headset: the solver threads' share of the cores, a niceness 0 (as the frame loop) to 19, or "
         "idle (only time no other thread wants: a waking frame takes the core at once, but a machine "
         "busy with other work starves previews and commits)")
      ->check(CLI::IsMember({"idle"}) | CLI::Range(0, 19))
      ->default_str("10");
  cmd->add_option(
         "--solver-cpus", o->solver_cpus,
         "Headset: CPUs of the solver's own (e.g. 3, 2-3, or auto: the last physical core), the frame loop "
         "and the threads it starts (lavapipe's, LP_NUM_THREADS as many unless set) keep the others, so a "
         "solve never takes a frame's core; none: all share them")
      ->default_str("none")
      ->check(
          [](const std::string& value) -> std::string {  // named at once, before the model loads
            const std::vector<int> allowed = deform::allowed_cpus();
            if (allowed.empty()) return "";  // the review says it cannot pin here
            try {
              (void)split_cpus(value, allowed);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return "";
          },
          "CPU list");
  add_life_size_options(*cmd, o->life_size);
  cmd->callback([o, samples, up] {
    o->samples_given = samples->count() > 0;
    o->up_given = up->count() > 0;
    (void)messages_off_stdout({o->out, o->record, o->events});
    // A recording is the one copy of a session: one already at --record is not replaced (a replay's own
    // recording, which it rewrites each time, does not come this way).
    if (!o->record.empty() && !deform::holds_descriptor(o->record)) {
      std::error_code error;
      if (std::filesystem::is_regular_file(o->record, error) &&
          std::filesystem::file_size(o->record, error) > 0 && !error)
        throw CommandError(o->record +
                           ": --record: a file is already there (an earlier session?); give "
                           "another name or remove it first");
    }
    run_review(*o);
  });
}

}  // namespace pushpull::app
