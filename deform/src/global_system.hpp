// Private: the global step of the local-global solver, Q_ff X_f^T = B_f^T - Q_fc X_c^T, with Q_ff
// prefactored by a sparse LDL^T (symbolic analysis once, numeric refactorization when Q's values change).
// The factorization is Eigen's SimplicialLDLT with AMD, or on large regions CHOLMOD's simplicial LDL^T with
// METIS nested dissection when the build found CHOLMOD (PUSHPULL_HAVE_CHOLMOD; the crossover is measured in
// global_system.cpp); the triangular solves are ours either way (split_solve.cpp). The class layout does not
// depend on the backend, and no CHOLMOD type appears here.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
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
  // Automatic: CHOLMOD from its crossover size on (when built in), else Eigen. Eigen / Cholmod force one
  // (tests compare them); Cholmod without CHOLMOD built in falls back to Eigen (see cholmod_available).
  enum class Backend { Automatic, Eigen, Cholmod };
  [[nodiscard]] static bool cholmod_available();

  GlobalSystem();
  ~GlobalSystem();
  GlobalSystem(GlobalSystem&&) noexcept;
  GlobalSystem& operator=(GlobalSystem&&) noexcept;
  GlobalSystem(const GlobalSystem&) = delete;
  GlobalSystem& operator=(const GlobalSystem&) = delete;

  // Q: n by n symmetric (both triangles stored), local vertices [0, n_free) free, the rest constrained.
  // Extracts the blocks' patterns and runs the symbolic analysis (fill-reducing ordering, elimination tree).
  void analyze(const Eigen::SparseMatrix<double>& Q, int n_free, Backend backend = Backend::Automatic);
  // The same as analyze(Q', n_free, its backend) for a Q' with the pattern `analysed` was analysed for,
  // reusing its analysis (the ordering: METIS takes longer than a numeric factorization at 100K) instead of
  // redoing it. `analysed` must be analysed; it is not changed.
  void analyze_like(const GlobalSystem& analysed);
  [[nodiscard]] int free_count() const { return n_free_; }
  // Copies Q's current values into the blocks and refactors (reusing the analysis). Throws FactorizationError
  // if Q_ff is singular or indefinite (a pivot of its LDL^T at most 1e-13 times the largest). Deterministic:
  // the same Q gives a bit-identical factor.
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
  struct Factor;  // the backend's symbolic analysis and numeric factor (global_system.cpp)
  std::unique_ptr<Factor> factor_;
  void analyze_factor(Backend backend);  // symbolic analysis of qff_ into a new factor_ (n_free_ > 0)
  // Numeric LDL^T of qff_ reusing factor_'s analysis; sets the L view, d_ and perm_. Throws
  // FactorizationError on a zero pivot (the pivot check of factorize() catches the rest).
  void factor_numeric();
  // The unit lower triangular factor L of P Q_ff P^T = L D L^T, owned by factor_, in compressed columns:
  // column j's strictly lower entries are [l_column_[j] + l_diagonal_slots_, l_column_[j + 1]) of
  // l_row_/l_value_, in a fixed order (a backend may store D in the first slot of each column).
  const int* l_column_ = nullptr;
  const int* l_row_ = nullptr;
  const double* l_value_ = nullptr;
  int l_diagonal_slots_ = 0;
  Eigen::VectorXd d_, inv_d_;  // D of the factor and its inverse
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
