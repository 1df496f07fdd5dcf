#include "number_checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pushpull::app {

namespace {

// wanted: "a finite number > 1"; bounded: compare with bound (else any finite number); at_most: and <= it.
CLI::Validator finite_check(std::string wanted, bool bounded, double bound, bool strict,
                            double at_most = HUGE_VAL) {
  return CLI::Validator(
      [bounded, bound, strict, at_most, wanted](std::string& input) -> std::string {
        // strtod as CLI11 reads numbers: underflow is a number (0 or subnormal), overflow is too large.
        const char* begin = input.c_str();
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0') return "'" + input + "' is not a number (expected " + wanted + ")";
        if (errno == ERANGE && std::abs(value) > 1.0)
          return input + " is too large (expected " + wanted + ")";
        if (!std::isfinite(value) || (bounded && (strict ? !(value > bound) : !(value >= bound))) ||
            !(value <= at_most))
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

CLI::Validator finite_in(double low, double high) {
  char text[96];
  std::snprintf(text, sizeof text, "a finite number from %g to %g", low, high);
  return finite_check(text, true, low, false, high);
}

CLI::Validator whole_number_in(long low, long high) {
  const std::string wanted = "a whole number from " + std::to_string(low) + " to " + std::to_string(high);
  return CLI::Validator(
      [low, high, wanted](std::string& input) -> std::string {
        const char* begin = input.c_str();
        char* end = nullptr;
        errno = 0;
        const long value = std::strtol(begin, &end, 10);
        if (end == begin || *end != '\0')
          return "'" + input + "' is not a whole number (expected " + wanted + ")";
        if (errno == ERANGE || value < low || value > high) return input + " must be " + wanted;
        return "";
      },
      wanted);
}

}  // namespace pushpull::app
