// Private: the global step of the local-global solver, Q_ff X_f^T = B_f^T - Q_fc X_c^T, with Q_ff
// prefactored by a sparse LDL^T (symbolic analysis once, numeric refactorization when Q's values change).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <vector>

#include "helper_thread.hpp"

namespace pushpull::deform::detail {

// Q_ff could not be factored: what() says how (the failing pivot); the Deformer adds the method, the
// region's size and what to try (see factorization_failure_message in deformer.cpp).
class FactorizationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GlobalSystem {
 public:
  // Q: n by n symmetric (both triangles stored), local vertices [0, n_free) free, the rest constrained.
  // Extracts the blocks' patterns and runs the symbolic analysis (fill-reducing ordering, elimination tree).
  void analyze(const Eigen::SparseMatrix<double>& Q, int n_free);
  // Copies Q's current values into the blocks and refactors. Throws FactorizationError if Q_ff is singular or
  // indefinite (a pivot of its LDL^T at most 1e-13 times the largest).
  void factorize(const Eigen::SparseMatrix<double>& Q);
  // -Q_fc X_c for the constrained columns X_c (3 by n - n_free): 3 by n_free.
  [[nodiscard]] Eigen::Matrix3Xd constrained_rhs(const Eigen::Matrix3Xd& X_c) const;
  // Solves Q_ff Y^T = B^T in place (B: 3 by n_free), the three coordinates in one pass over the factor.
  // The triangular solves run in two elimination subtrees plus their common ancestors ("top"), a fixed split
  // made at factorization; `threads`, when given, runs the two subtrees concurrently (same results).
  // Thread-safety: const, may be called concurrently (with distinct `threads`).
  void solve_in_place(Eigen::Matrix3Xd& B, HelperThread* threads = nullptr) const;

 private:
  int n_free_ = 0;
  Eigen::SparseMatrix<double> qff_, qfc_;
  std::vector<int> qff_source_, qfc_source_;  // value index in Q of each value of the blocks
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  Eigen::VectorXd inv_d_;
  Eigen::VectorXi perm_;  // P: b_perm[perm_[i]] = b[i]

  // Split of the triangular solves (split_solve.cpp): subtree columns of each part (ascending), the top
  // columns (ascending), and per factor entry the workspace column its forward update goes to: its row, or
  // for a part's entry in a top row, that part's accumulator column n + part * #top + slot of the row.
  void plan_split();
  std::vector<int> part_columns_[2], top_columns_;
  std::vector<int> forward_target_;
  std::vector<int> planned_outer_, planned_inner_;  // the factor pattern the split was planned for
};

}  // namespace pushpull::deform::detail
