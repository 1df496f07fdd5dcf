// Method names: the single place that maps energies to their command-line spelling.
#include "pushpull/deform/method.hpp"

#include <stdexcept>

namespace pushpull::deform {

std::string_view method_name(Method method) {
  switch (method) {
    case Method::ArapS:
      return "arap-s";
    case Method::ArapSR:
      return "arap-sr";
    case Method::ArapM:
      return "arap-m";
    case Method::ArapN:
      return "arap-n";
    case Method::SrArap:
      return "sr-arap";
    case Method::ArapH:
      return "arap-h";
    case Method::ArapSrH:
      return "arap-sr-h";
    case Method::Asan:
      return "asan";
  }
  throw std::invalid_argument("method_name: invalid Method value " +
                              std::to_string(static_cast<int>(method)));
}

Method parse_method(std::string_view name) {
  std::string valid;
  for (Method m : kAllMethods) {
    if (method_name(m) == name) return m;
    valid += valid.empty() ? "" : ", ";
    valid += method_name(m);
  }
  throw std::invalid_argument("unknown deformation method '" + std::string(name) + "' (valid: " + valid +
                              ")");
}

}  // namespace pushpull::deform
