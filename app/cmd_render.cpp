#include "commands.hpp"

namespace pushpull::app {

// Not registered yet: `pushpull render` arrives with its issue.
void add_render_command(CLI::App& /*root*/) {}

}  // namespace pushpull::app
