#include "review_colour.hpp"

namespace pushpull::app {

ReviewColour next_colour(ReviewColour c) {
  switch (c) {
    case ReviewColour::Material:
      return ReviewColour::Displacement;
    case ReviewColour::Displacement:
      return ReviewColour::CurvatureSign;
    case ReviewColour::CurvatureSign:
      return ReviewColour::Material;
  }
  return ReviewColour::Material;
}

const char* colour_name(ReviewColour c) {
  switch (c) {
    case ReviewColour::Material:
      return "material";
    case ReviewColour::Displacement:
      return "displacement";
    case ReviewColour::CurvatureSign:
      return "curvature-sign";
  }
  return "?";
}

std::optional<ReviewColour> parse_colour(std::string_view name) {
  for (const ReviewColour c :
       {ReviewColour::Material, ReviewColour::Displacement, ReviewColour::CurvatureSign})
    if (name == colour_name(c)) return c;
  return std::nullopt;
}

}  // namespace pushpull::app
