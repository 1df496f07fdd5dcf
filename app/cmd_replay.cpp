// `pushpull replay`: a recorded review session run again headless (replay_session.hpp).
#include "commands.hpp"
#include "method_check.hpp"
#include "number_checks.hpp"
#include "replay_compare.hpp"
#include "replay_session.hpp"

#include "pushpull/deform/method.hpp"

#include <CLI/CLI.hpp>
#include <limits>

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushpull::app {

void add_replay_command(CLI::App& root) {
  auto o = std::make_shared<ReplayOptions>();
  auto mu = std::make_shared<double>(0.0);  // outlives this function with the command, as `o` does
  auto compare = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = root.add_subcommand(
      "replay",
      "Replay a session recorded by `pushpull review` (--record) headless: the same review loop against the\n"
      "simulated OpenXR runtime (xr/sim) with the recording as its input on the virtual clock. Writes the model\n"
      "after every commit and at the end, the metrics per commit, both eyes at each release, pictures and\n"
      "report.html into --out, and checks every commit's hash against the recording (bit-identical; with another\n"
      "--method or --mu each commit's d is compared instead, within 1e-9 model units).");
  cmd->add_option("session", o->recording, "Session recording (.jsonl)")->required();
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--model", o->model, "The model file, when it is no longer where the recording says");
  // A method name is checked when the command line is read, before any replay runs.
  cmd->add_option("--method", o->method,
                  "Replay with another method (asan, arap-s, arap-sr, arap-m, arap-n, ...)")
      ->check(method_name());
  auto* mu_option =
      cmd->add_option("--mu", *mu, "Replay with another ASAN stiffness ratio")->check(finite_above(1.0));
  cmd->add_option("--eye-size", o->eye_size, "Per-eye image size W H of the simulated headset")
      ->expected(2)
      ->check(whole_number_in(16, 16384))
      ->capture_default_str();
  cmd->add_option("--picture-size", o->picture_size, "Size W H of the report's pictures")
      ->expected(2)
      ->check(whole_number_in(16, 16384))
      ->capture_default_str();
  cmd->add_option(
         "--compare", *compare,
         "Replay once per method (e.g. asan,arap-sr) into OUT/METHOD and write OUT/compare.html side by side")
      ->delimiter(',')
      ->check(method_name());
  cmd->add_option(
         "--capture-every", o->capture_every,
         "Also write both eyes every N frames into OUT/eyes (default: at each release and at the end)")
      ->check(whole_number_in(0, std::numeric_limits<int>::max()));
  cmd->add_flag("--no-pictures", [o](std::int64_t) { o->pictures = false; }, "Leave the pictures out of the report");
  cmd->callback([o, mu, mu_option, compare] {
    if (mu_option->count() > 0) o->mu = *mu;
    if (!compare->empty()) {
      if (!o->method.empty()) throw UsageError("give --method or --compare, not both");
      for (std::size_t i = 0; i < compare->size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if ((*compare)[i] == (*compare)[j])
            throw UsageError("--compare names " + (*compare)[i] +
                             " twice (each method replays into its own folder)");
      run_replay_comparison(*o, *compare);
      return;
    }
    run_replay(*o);
  });
}

}  // namespace pushpull::app
