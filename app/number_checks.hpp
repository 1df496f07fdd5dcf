// Command-line checks for real-valued options (CLI11 validators): finite, and above or at least a bound. The
// messages say what the value must be ("must be a finite number > 1"), not a range of 300 digits, and refuse
// nan and inf, which comparisons alone let through. Thread-safety: plain values.
#pragma once

#include <CLI/CLI.hpp>

namespace pushpull::app {

// A finite number > bound (strict) or >= bound.
[[nodiscard]] CLI::Validator finite_above(double bound, bool strict = true);
// Any finite number.
[[nodiscard]] CLI::Validator finite_number();

}  // namespace pushpull::app
