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
#pragma once

#include <Eigen/Core>
#include <vector>

#include "helper_thread.hpp"

namespace pushpull::deform::detail {

class Anderson {
 public:
  Anderson(int window, Eigen::Index dimension, int min_pairs = 1);
  // window >= 1; min_pairs is clamped to [1, window].
  // x: current iterate, g = G(x). Returns the accelerated next iterate (g itself for the first min_pairs
  // calls after construction or reset, and after a window whose normal equations give no finite solution,
  // which also resets). The vectors' two halves are processed and their dot products summed separately (on
  // two threads when `threads` is given; the same results either way).
  [[nodiscard]] Eigen::VectorXd step(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& g,
                                     HelperThread* threads = nullptr);
  void reset() { count_ = 0; }

 private:
  int window_;
  int min_pairs_;
  int count_ = 0;  // iterations since reset
  Eigen::VectorXd prev_f_, prev_g_;
  Eigen::MatrixXd dF_, dG_;  // dimension by window, circular
  Eigen::MatrixXd gram_;     // window by window, dF^T dF, updated one column per step
};

}  // namespace pushpull::deform::detail
