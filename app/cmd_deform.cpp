#include "commands.hpp"

namespace pushpull::app {

// Not registered yet: `pushpull deform` arrives with its issue.
void add_deform_command(CLI::App& /*root*/) {}

}  // namespace pushpull::app
