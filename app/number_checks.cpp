#include "number_checks.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace pushpull::app {

namespace {

// wanted: "a finite number > 1"; bounded: compare with bound (else any finite number).
CLI::Validator finite_check(std::string wanted, bool bounded, double bound, bool strict) {
  return CLI::Validator(
      [bounded, bound, strict, wanted](std::string& input) -> std::string {
        double value = 0.0;
        std::size_t used = 0;
        try {
          value = std::stod(input, &used);
        } catch (const std::exception&) {
          return "'" + input + "' is not a number (expected " + wanted + ")";
        }
        if (used != input.size()) return "'" + input + "' is not a number (expected " + wanted + ")";
        if (!std::isfinite(value) || (bounded && (strict ? !(value > bound) : !(value >= bound))))
          return input + " must be " + wanted;
        return "";
      },
      wanted);
}

}  // namespace

CLI::Validator finite_above(double bound, bool strict) {
  char text[64];
  std::snprintf(text, sizeof text, "a finite number %s %g", strict ? ">" : ">=", bound);
  return finite_check(text, true, bound, strict);
}

CLI::Validator finite_number() {
  return finite_check("a finite number", false, 0.0, false);
}

}  // namespace pushpull::app
