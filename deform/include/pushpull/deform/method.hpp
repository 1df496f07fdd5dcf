// pushpull::deform::Method: the deformation energies the solver can minimise, selectable by name.
//
// Every method is an as-rigid-as-possible (ARAP) energy of the form
//   E(p') = sum_c min_{R_c in SO(3)} sum_{(i,j,w) in cluster c} w |(p'_i - p'_j) - R_c (p_i - p_j)|^2
// plus, for sr-arap, arap-h and arap-sr-h, a coupling or bending term; they differ in how clusters and
// weights are built. See deformer.hpp for the formulas and references of each.
//
// Thread-safety: free functions without state.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace pushpull::deform {

enum class Method {
  ArapS,    // "arap-s":    Sorkine & Alexa 2007, spokes, per-vertex rotations
  ArapSR,   // "arap-sr":   Chao et al. 2010, spokes and rims, per-vertex rotations
  ArapM,    // "arap-m":    Zhao et al. (membrane), per-triangle rotations
  ArapN,    // "arap-n":    Chen et al. 2017, per-vertex rotations over an n-ring patch
  SrArap,   // "sr-arap":   Levi & Gotsman 2014, arap-sr plus smooth rotations
  ArapH,    // "arap-h":    Zhao et al.'s hybrid: arap-m plus a mean-curvature term with per-vertex rotations
  ArapSrH,  // "arap-sr-h": arap-sr plus the same mean-curvature term, borrowing each vertex's arap-sr
            // rotation
  Asan,  // "asan":      Le Vaou et al. 2020, arap-sr (or arap-m) with cotangent weights of a stretched copy
};

// All methods, in the order above.
inline constexpr std::array kAllMethods = {Method::ArapS,  Method::ArapSR, Method::ArapM,   Method::ArapN,
                                           Method::SrArap, Method::ArapH,  Method::ArapSrH, Method::Asan};

// The command-line name of a method ("arap-s", "arap-sr", "arap-m", "arap-n", "sr-arap", "arap-h",
// "arap-sr-h", "asan").
[[nodiscard]] std::string_view method_name(Method method);

// Inverse of method_name (case-sensitive). Throws std::invalid_argument naming the bad value and listing the
// valid names.
[[nodiscard]] Method parse_method(std::string_view name);

}  // namespace pushpull::deform
