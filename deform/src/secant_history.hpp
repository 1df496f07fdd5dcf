// Private: the last secant pairs of a fixed-point iteration x -> g = G(x), kept once for the two users that
// read them every iteration: Anderson acceleration (anderson.hpp) and the contraction estimate
// (error_estimate.hpp).
//
// Why one history: both kept their own differences of the same iterates and images (Anderson dF and dG, the
// estimate dX and dG, dX = dG - dF) and refreshed their Gram matrices with a dot product per stored column
// and per matrix, each reading whole columns: at 100K free vertices a column is 2.4 MB and the two read about
// 70 columns an iteration. Here one pass over the vectors, in cache-sized chunks, writes the new pair and
// refreshes every Gram entry with the stored columns (each read once), and the plain step's largest vertex
// move comes out of the same pass.
//
// Stored: dF = f - f_prev and dG = g - g_prev with f = g - x (the residual). dX = dG - dF is not stored;
// its Gram entries follow from these without cancellation where it matters: for a mode that contracts at
// rate lambda in [0, 1], |dF|, |dG| <= |dX|, whereas dF from dG - dX would cancel as lambda -> 1.
// Deterministic: the vectors are split into two fixed halves (at a multiple of 3) and their chunks summed
// in a fixed order, on two threads when given one: the same bits either way.
// Memory: 2 x window columns of `dimension` doubles, and two more vectors. Thread-safety: none (one solve).
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "helper_thread.hpp"

namespace pushpull::deform::detail {

class SecantHistory {
 public:
  SecantHistory(int window, Eigen::Index dimension);  // window >= 1 (clamped)

  // Records the iterate x and its image g = G(x) (both of `dimension`). From the second call on, the pair
  // (f - f_prev, g - g_prev) replaces the oldest stored one, and the Gram entries of the stored pairs and
  // their projections on the new f are refreshed. Returns the largest squared norm of f over consecutive
  // triples of entries (a vertex's move when the vectors hold 3 x n coordinates; a trailing partial triple
  // counts too).
  double add(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g,
             HelperThread* threads = nullptr);

  [[nodiscard]] int window() const { return window_; }
  [[nodiscard]] long pairs() const { return pairs_; }  // pairs recorded since construction
  [[nodiscard]] int stored() const { return static_cast<int>(std::min<long>(pairs_, window_)); }
  // The storage column of the k-th newest pair, k in [0, stored()).
  [[nodiscard]] int column(int k) const {
    return static_cast<int>(((pairs_ - 1 - k) % window_ + window_) % window_);
  }

  // Over storage columns i, j < stored(): ff(i, j) = dF_i . dF_j, fg(i, j) = dF_i . dG_j, gg(i, j) = dG_i .
  // dG_j.
  [[nodiscard]] const Eigen::MatrixXd& ff() const { return ff_; }
  [[nodiscard]] const Eigen::MatrixXd& fg() const { return fg_; }
  [[nodiscard]] const Eigen::MatrixXd& gg() const { return gg_; }
  // dF_i . f for the last recorded f (Anderson's right-hand side).
  [[nodiscard]] const Eigen::VectorXd& f_on_dF() const { return f_on_dF_; }

  // out = g - sum_k gamma(k) dG_column(k) over the newest gamma.size() <= stored() pairs. Returns whether
  // every entry of out is finite.
  bool extrapolate(const Eigen::Ref<const Eigen::VectorXd>& g, const Eigen::VectorXd& gamma,
                   Eigen::Ref<Eigen::VectorXd> out, HelperThread* threads = nullptr) const;

 private:
  int window_;
  Eigen::Index dimension_;
  long pairs_ = 0;
  bool has_previous_ = false;
  Eigen::VectorXd previous_f_, previous_g_;
  Eigen::MatrixXd dF_, dG_;       // dimension by window, circular
  Eigen::MatrixXd ff_, fg_, gg_;  // window by window
  Eigen::VectorXd f_on_dF_;       // window
};

}  // namespace pushpull::deform::detail
