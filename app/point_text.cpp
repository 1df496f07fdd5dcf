#include "point_text.hpp"

#include <cmath>
#include <cstdio>

namespace pushpull::app {
namespace {

std::string coordinate_text(double metres) {
  char text[64];
  if (!(std::abs(metres) < 1e12)) {
    std::snprintf(text, sizeof text, "%.6g", metres);
    return text;
  }
  const double rounded = std::round(metres * 1e6) / 1e6 + 0.0;  // + 0.0: no negative zero
  std::snprintf(text, sizeof text, "%.6f", rounded);
  std::string out = text;
  out.erase(out.find_last_not_of('0') + 1);
  if (!out.empty() && out.back() == '.') out.pop_back();
  return out == "-0" ? "0" : out;
}

}  // namespace

std::string point_in_metres_text(const Eigen::Vector3d& metres) {
  return coordinate_text(metres.x()) + " " + coordinate_text(metres.y()) + " " + coordinate_text(metres.z());
}

}  // namespace pushpull::app
