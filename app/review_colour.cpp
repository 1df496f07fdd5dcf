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

}  // namespace pushpull::app
