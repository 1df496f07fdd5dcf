// Command-line checks for numeric options (CLI11 validators): finite, and above or at least a bound; whole
// and within bounds. The messages say what the value must be ("must be a finite number > 1"), not a range of
// 300 digits, and refuse nan and inf, which comparisons alone let through. Thread-safety: plain values.
#pragma once

#include <CLI/CLI.hpp>

namespace pushpull::app {

// A finite number > bound (strict) or >= bound.
[[nodiscard]] CLI::Validator finite_above(double bound, bool strict = true);
// Any finite number.
[[nodiscard]] CLI::Validator finite_number();
// A finite number from `low` to `high` (CLI::Range lets nan through: its comparisons are false).
[[nodiscard]] CLI::Validator finite_in(double low, double high);
// A whole number from `low` to `high` (for integer options: "1.5" is not a whole number, not "out of range").
[[nodiscard]] CLI::Validator whole_number_in(long low, long high);

}  // namespace pushpull::app
