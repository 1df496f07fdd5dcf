// Private: the cold solve's starting shape. The local-global iterations start from the rest positions with
// the constrained vertices at their targets; the first global step then spreads the handle's move
// harmonically (Q-weighted, a membrane: a cone under the handle), and the iterations spend their first tens
// of steps rounding it into the bending shape the energy wants. SmoothStart spreads the constrained vertices'
// displacements biharmonically instead: the free displacements D_f minimise |L D|^2 summed over every vertex
// of the region (constrained rows included, so the surface leaves the handle and the fixed border smoothly),
// with L the uniform graph Laplacian of the global matrix's pattern (the region's edges; arap-n: its rings).
// Uniform weights keep it positive definite on any tessellation (slivers, needles), and being independent of
// the method's weights and of d it is factored once per region, reusing the analysis (the fill-reducing
// ordering) of the region's global matrix, whose pattern it has. When it is used and what it gains: see
// DeformOptions::smooth_start_min_free.
//
// The biharmonic system (L^2)_ff D_f = -(L^2)_fc D_c is solved by conjugate gradients preconditioned with
// L_ff^-2 (two solves with the prefactored L_ff), starting from the harmonic spread L_ff D_f = -L_fc D_c;
// (L^2)_ff = L_ff^2 + L_fc L_cf differs from the preconditioner by the rows next to constrained vertices
// only.
//
// Thread-safety: prepare() mutates; displacement() is const and may run concurrently with distinct `threads`.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "global_system.hpp"
#include "helper_thread.hpp"

namespace pushpull::deform::detail {

class SmoothStart {
 public:
  // pattern: the global matrix Q (n by n, both triangles stored, local numbering: [0, n_free) free, the rest
  // constrained); only its pattern is read. analysed: Q's GlobalSystem, analysed for that pattern (its
  // analysis is reused). Builds L and factors L_ff (throws FactorizationError if a free component touches no
  // constrained vertex: the Deformer pins those, so it does not happen there).
  void prepare(const Eigen::SparseMatrix<double>& pattern, const GlobalSystem& analysed);
  [[nodiscard]] bool prepared() const { return prepared_; }

  struct Spread {
    Eigen::Matrix3Xd free;   // 3 by n_free: displacement of each free vertex (model units)
    int iterations = 0;      // conjugate-gradient iterations taken
    bool converged = false;  // relative residual <= kTolerance in every coordinate
  };
  // The displacements D_c (3 by n - n_free, constrained vertices in local order) spread over the free
  // vertices. Never throws for finite D_c; the result is finite.
  [[nodiscard]] Spread displacement(const Eigen::Matrix3Xd& D_c, HelperThread* threads = nullptr) const;

  // Conjugate-gradient stop: residual of (L^2)_ff D_f = rhs at most this fraction of its value at the
  // harmonic start, or kMaxIterations (it is a starting guess; the local-global solve takes it from there).
  static constexpr double kTolerance = 1e-3;
  static constexpr int kMaxIterations = 30;

 private:
  bool prepared_ = false;
  int n_free_ = 0;
  Eigen::SparseMatrix<double> laplacian_;  // n by n, uniform: -1 per edge, the degree on the diagonal
  GlobalSystem system_;                    // L_ff
  // (L (L [X_f; X_c]))_f for free columns X_f (3 by n_free) and constrained X_c (3 by n - n_free).
  [[nodiscard]] Eigen::Matrix3Xd apply_squared(const Eigen::Matrix3Xd& X_f,
                                               const Eigen::Matrix3Xd& X_c) const;
};

}  // namespace pushpull::deform::detail
