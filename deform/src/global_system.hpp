// Private: the global step of the local-global solver, Q_ff X_f^T = B_f^T - Q_fc X_c^T, with Q_ff
// prefactored by a sparse LDL^T (symbolic analysis once, numeric refactorization when Q's values change).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

namespace pushpull::deform::detail {

class GlobalSystem {
 public:
  // Q: n by n symmetric (both triangles stored), local vertices [0, n_free) free, the rest constrained.
  // Extracts the blocks' patterns and runs the symbolic analysis (fill-reducing ordering, elimination tree).
  void analyze(const Eigen::SparseMatrix<double>& Q, int n_free);
  // Copies Q's current values into the blocks and refactors. Throws std::runtime_error if Q_ff is singular.
  void factorize(const Eigen::SparseMatrix<double>& Q);
  // -Q_fc X_c for the constrained columns X_c (3 by n - n_free): 3 by n_free.
  [[nodiscard]] Eigen::Matrix3Xd constrained_rhs(const Eigen::Matrix3Xd& X_c) const;
  // Solves Q_ff Y^T = B^T in place (B: 3 by n_free), the three coordinates in one pass over the factor.
  void solve_in_place(Eigen::Matrix3Xd& B) const;

 private:
  int n_free_ = 0;
  Eigen::SparseMatrix<double> qff_, qfc_;
  std::vector<int> qff_source_, qfc_source_;  // value index in Q of each value of the blocks
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  Eigen::VectorXd inv_d_;
  Eigen::VectorXi perm_;  // P: b_perm[perm_[i]] = b[i]
};

}  // namespace pushpull::deform::detail
