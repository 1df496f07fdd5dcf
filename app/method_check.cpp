#include "method_check.hpp"

#include "pushpull/deform/method.hpp"

#include <stdexcept>
#include <string>

namespace pushpull::app {

CLI::Validator method_name() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        try {
          (void)deform::parse_method(name);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return "";
      },
      "METHOD");
}

CLI::Validator asan_base_name() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        return name == "arap-sr" || name == "arap-m"
                   ? ""
                   : "asan's base must be arap-sr or arap-m, got '" + name + "'";
      },
      "arap-sr|arap-m");
}

}  // namespace pushpull::app
