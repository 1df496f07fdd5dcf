#include "commands.hpp"

namespace pushpull::app {

// Not registered yet: `pushpull info` arrives with its issue.
void add_info_command(CLI::App& /*root*/) {}

}  // namespace pushpull::app
