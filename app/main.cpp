// pushpull: immersive design reviews of man-made shapes with As-Stiff-As-Needed deformation.
#include "commands.hpp"
#include "signals_held.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

namespace {
// The exit status of a command line that cannot be used (an unknown command or option, a value out of range),
// as for the shell's own builtins; 1 is an error while the command ran (a file, a solve).
constexpr int kUsageError = 2;
}  // namespace

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
    std::string commands;
    bool known = false;
    for (const CLI::App* command : root.get_subcommands({})) {
      commands += (commands.empty() ? "" : ", ") + command->get_name();
      known = known || (argc > 1 && command->get_name() == argv[1]);
    }
    if (argc > 1 && argv[1][0] != '-' && !known && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      std::fprintf(stderr, "pushpull: error: unknown command '%s' (the commands: %s; pushpull --help)\n",
                   argv[1], commands.c_str());
      return kUsageError;
    }
    // --help and --version end here too (success): CLI11 prints them.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return root.exit(e);
    // A command line that cannot be used: in the same form as every other error, with the command named
    // (CLI11 alone prints the bare message and exits 105-109 by the kind of mistake).
    std::string command, message = e.what();
    for (const CLI::App* sub : root.get_subcommands()) {
      command = " " + sub->get_name();
      // CLI11 checks what is required before what is left over: a mistyped option is named as such, not
      // as the missing argument it displaced.
      const std::vector<std::string> left = sub->remaining();
      if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && !left.empty())
        message = "unknown argument '" + left.front() + "'";
    }
    // An option given twice: CLI11 counts values, "--roi-radius: At Most 1 required but received 2",
    // "--displacement: At Most 3 required but received 6".
    if (const std::size_t at = message.find(": At Most ");
        at != std::string::npos && dynamic_cast<const CLI::ArgumentMismatch*>(&e) != nullptr) {
      unsigned per_use = 0, received = 0;
      if (std::sscanf(message.c_str() + at, ": At Most %u required but received %u", &per_use, &received) ==
              2 &&
          per_use > 0 && received > per_use && received % per_use == 0)
        message = message.substr(0, at) + " is given " + std::to_string(received / per_use) +
                  " times; give it once";
    }
    std::fprintf(stderr, "pushpull%s: error: %s\n(pushpull%s --help lists the options)\n", command.c_str(),
                 message.c_str(), command.c_str());
    return kUsageError;
  } catch (const pushpull::app::UsageError& e) {  // options the command found unusable together
    std::string command;
    for (const CLI::App* sub : root.get_subcommands()) command = " " + sub->get_name();
    std::fprintf(stderr, "pushpull%s: error: %s\n(pushpull%s --help lists the options)\n", command.c_str(),
                 e.what(), command.c_str());
    return kUsageError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pushpull: error: %s\n", e.what());
    pushpull::app::raise_held_signal();  // a Ctrl-C held while the failed write ran (signals_held.hpp)
    return 1;
  }
  return 0;
}
