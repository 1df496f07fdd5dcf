#include "solver_errors.hpp"

#include <cstdio>

namespace pushpull::deform::detail {
namespace {

std::string region_text(const RegionSize& region) {
  return "a region of " + std::to_string(region.vertices) + " vertices (" + std::to_string(region.free) +
         " free, " + std::to_string(region.handle) + " handle, " + std::to_string(region.fixed) + " fixed)";
}

constexpr const char* kArapSAdvice =
    "arap-s weights its spokes by (cot a + cot b) / 2, which is negative across obtuse triangles, so it is "
    "not "
    "positive semidefinite on every mesh; use arap-sr or asan, or a smaller region (--roi-radius)";

}  // namespace

std::string factorization_failure_message(Method method, const RegionSize& region, std::string_view reason,
                                          double mu) {
  // Le Vaou et al. 2020, section 3.2 and Fig. 3: the spokes' weights turn negative across obtuse triangles,
  // and the per-vertex energies stop being positive semidefinite.
  std::string advice =
      method == Method::ArapS
          ? kArapSAdvice
          : "its weights are positive semidefinite by construction (mollified cotangents), so part of the "
            "region is held by no stiffness or the weights span too many orders of magnitude; check the mesh "
            "for degenerate or disconnected pieces, or try a smaller region (--roi-radius)";
  // asan's stretch spreads its weights over about mu^2 (a stretched triangle's cotangents): far beyond the
  // paper's 100 that alone can exhaust a double's digits (the bundled bonnet: mu = 1e8 fails, 1e6 solves).
  if (method == Method::Asan && mu > 1e4) {
    char text[160];
    std::snprintf(
        text, sizeof text,
        "; first, asan's stretch mu = %.6g spreads the weights over ~mu^2: a smaller mu (the paper's "
        "100) keeps them within a double's digits",
        mu);
    advice += text;
  }
  return "deformer: " + std::string(method_name(method)) + ": " + std::string(reason) + " for " +
         region_text(region) + ": " + advice;
}

std::string negative_energy_message(Method method, const RegionSize& region, double energy,
                                    double initial_energy) {
  char numbers[96];
  std::snprintf(numbers, sizeof numbers,
                initial_energy < 0.0 ? "%.6g (%.6g at the start)" : "%.6g (from %.6g at the start)", energy,
                initial_energy);
  return "deformer: " + std::string(method_name(method)) + ": the energy " +
         (initial_energy < 0.0 ? "is negative, " : "went negative, ") + numbers + ", on " +
         region_text(region) + ", so the result is not a meaningful shape: " + kArapSAdvice;
}

}  // namespace pushpull::deform::detail
