// Private: Anderson acceleration of a fixed-point iteration x <- G(x) (type II, window m), as used for
// local-global solvers by Peng, Deng, Zhang, Liu, "Anderson acceleration for geometry optimization and
// physics simulation", ACM TOG 37(4), 2018. The caller keeps the energy safeguard: when the accelerated
// iterate raises the energy it falls back to G(x) and calls reset().
//
// min_pairs: the secant pairs the window must hold before it extrapolates (after construction and after
// every reset; G(x) itself until then). With 1 (plain Anderson) the first steps after a reset extrapolate
// from one or two pairs; on asan's stiff anisotropic problems that extrapolation overshoots along the slow
// mode, the energy rises, the safeguard resets, and the solve falls into a cycle of a plain step and a
// rejected one (each rejection an extra local step): on the real car's nose (stopping_bench, AsamVehicle,
// asan), every other iteration from 29 to 159 of the 2 m region's 277. Waiting for a full window there took
// 167 iterations (1 m region: 217 -> 145).
// The secant pairs come from a SecantHistory (secant_history.hpp) that the solver shares with its error
// estimate; a standalone Anderson (the three-argument constructor) keeps one of its own.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "helper_thread.hpp"
#include "secant_history.hpp"

namespace pushpull::deform::detail {

class Anderson {
 public:
  // window >= 1; min_pairs is clamped to [1, window]. Reads its pairs from the caller's history, whose window
  // must be at least this one.
  explicit Anderson(int window, int min_pairs = 1);
  // The same with a history of its own for vectors of `dimension` (the step(x, g) form).
  Anderson(int window, Eigen::Index dimension, int min_pairs);

  // history: the pairs so far, its last recorded (x, g) being the current iterate x and g = G(x). Writes the
  // extrapolated next iterate into `next` and returns true; returns false (next untouched: the next iterate
  // is g itself) for the first min_pairs calls after construction or reset, and after a window whose normal
  // equations give no finite solution (which also resets) or whose extrapolation is not finite.
  bool step(const SecantHistory& history, const Eigen::Ref<const Eigen::VectorXd>& g,
            Eigen::Ref<Eigen::VectorXd> next, HelperThread* threads = nullptr);
  // Standalone (own history): records (x, g) and returns the next iterate (g itself where step returns
  // false).
  [[nodiscard]] Eigen::VectorXd step(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& g,
                                     HelperThread* threads = nullptr);
  // Forgets the pairs so far: the next call's pair (which reaches back before the reset) is not used either.
  void reset() { reset_pending_ = true; }

 private:
  int window_;
  int min_pairs_;
  long base_ = 0;  // the history's pair count when the usable pairs began
  bool reset_pending_ = false;
  std::optional<SecantHistory> own_;
};

}  // namespace pushpull::deform::detail
