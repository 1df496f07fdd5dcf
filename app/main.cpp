// pushpull: immersive design reviews of man-made shapes with As-Stiff-As-Needed deformation.
#include "commands.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  // Line by line also into a file or a pipe (a review's log survives a kill; its lines interleave with
  // stderr's in the order they happened).
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // A reader that goes away (a FIFO or pipe named as an output, closed early) is a write error the command
  // reports with the file's name, not a silent death by SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App root{
      "pushpull: push and pull a tessellated design model with As-Stiff-As-Needed deformation\n"
      "(Le Vaou et al., Computer-Aided Design 121, 2020) and the ARAP family it is compared with."};
  root.set_version_flag("--version", PUSHPULL_VERSION);
  root.require_subcommand(1);
  pushpull::app::add_deform_command(root);
  pushpull::app::add_info_command(root);
  pushpull::app::add_render_command(root);
  pushpull::app::add_review_command(root);
  pushpull::app::add_replay_command(root);

  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A first word that is neither an option nor a command: say so, with the commands there are (CLI11
    // would only say that a subcommand is required).
    if (argc > 1 && argv[1][0] != '-' && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      std::string commands;
      for (const CLI::App* command : root.get_subcommands({}))
        commands += (commands.empty() ? "" : ", ") + command->get_name();
      std::fprintf(stderr, "pushpull: error: unknown command '%s' (the commands: %s; pushpull --help)\n",
                   argv[1], commands.c_str());
      return 109;  // CLI11's exit code for an unknown argument
    }
    return root.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pushpull: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
