// The command-line check of a deformation method's name (CLI11 validator): a name deform::parse_method does
// not know is refused while the command line is read, as a value out of range (exit 2, the command named),
// with parse_method's message listing the valid names. Thread-safety: plain values.
#pragma once

#include <CLI/CLI.hpp>

namespace pushpull::app {

// Any method name parse_method accepts.
[[nodiscard]] CLI::Validator method_name();
// asan's membrane energy (--asan-base): arap-sr or arap-m.
[[nodiscard]] CLI::Validator asan_base_name();

}  // namespace pushpull::app
