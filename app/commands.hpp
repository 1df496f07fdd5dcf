// Subcommands of the `pushpull` executable. Each add_*_command registers one subcommand (options,
// --help text, callback) on the root CLI11 app. A callback reports failure by throwing
// pushpull::app::CommandError (or any std::exception) whose message names the file and the problem;
// main() prints it and exits with status 1. Options that cannot be used together or make no sense (found
// after parsing: a zero direction, a missing companion option) throw UsageError: main() names the command
// and exits with status 2, as for the options CLI11 refuses itself.
#pragma once

#include <stdexcept>
#include <string>

namespace CLI {
class App;
}

namespace pushpull::app {

struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct UsageError : CommandError {
  using CommandError::CommandError;
};

void add_deform_command(CLI::App& root);  // pushpull deform: one push/pull on a model
void add_info_command(CLI::App& root);    // pushpull info: what is in a model
void add_render_command(CLI::App& root);  // pushpull render: a PNG of a model or result
void add_review_command(CLI::App& root);  // pushpull review: push/pull in an OpenXR headset
void add_replay_command(CLI::App& root);  // pushpull replay: a recorded review session, headless

}  // namespace pushpull::app
