// Private: the readable errors of the solver (what failed, for which method and region, what to try).
#pragma once

#include <string>
#include <string_view>

#include "pushpull/deform/method.hpp"

namespace pushpull::deform::detail {

struct RegionSize {
  int vertices = 0;  // all vertices of the region of interest (free + handle + fixed + pinned)
  int free = 0;
  int handle = 0;
  int fixed = 0;
};

// The message of the std::runtime_error the Deformer throws when the global matrix cannot be factored:
// "deformer: <method>: <reason> for a region of <n> vertices (...): <what to try>".
// `reason` is FactorizationError::what(). Thread-safety: pure function.
[[nodiscard]] std::string factorization_failure_message(Method method, const RegionSize& region,
                                                        std::string_view reason, double mu = 100.0);

// The message of the std::runtime_error the Deformer throws when arap-s ends with a negative energy: its
// spokes carry negative weights (cot a + cot b < 0) strong enough that the energy is not bounded below by 0
// and the shape is not meaningful (Le Vaou et al. 2020, Fig. 3). `energy` and `initial_energy`: model
// units^2. Thread-safety: pure function.
[[nodiscard]] std::string negative_energy_message(Method method, const RegionSize& region, double energy,
                                                  double initial_energy);

}  // namespace pushpull::deform::detail
