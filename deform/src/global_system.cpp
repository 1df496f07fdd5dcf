#include "global_system.hpp"

#include <stdexcept>
#include <string>

namespace pushpull::deform::detail {

void GlobalSystem::analyze(const Eigen::SparseMatrix<double>& Q, int n_free) {
  n_free_ = n_free;
  const int n = static_cast<int>(Q.cols());
  std::vector<Eigen::Triplet<double>> ff, fc;
  qff_source_.clear();
  qfc_source_.clear();
  for (int c = 0; c < n; ++c) {
    for (int p = Q.outerIndexPtr()[c]; p < Q.outerIndexPtr()[c + 1]; ++p) {
      const int r = Q.innerIndexPtr()[p];
      if (r >= n_free) continue;
      if (c < n_free) {
        if (r >= c) ff.emplace_back(r, c, 1.0);  // lower triangle is all LDL^T reads
      } else {
        fc.emplace_back(r, c - n_free, 1.0);
      }
    }
  }
  qff_.resize(n_free, n_free);
  qff_.setFromTriplets(ff.begin(), ff.end());
  qfc_.resize(n_free, n - n_free);
  qfc_.setFromTriplets(fc.begin(), fc.end());
  qff_.makeCompressed();
  qfc_.makeCompressed();
  // Triplets were generated in column-major order without duplicates, so value k of a block is triplet k.
  for (int c = 0; c < n; ++c) {
    for (int p = Q.outerIndexPtr()[c]; p < Q.outerIndexPtr()[c + 1]; ++p) {
      const int r = Q.innerIndexPtr()[p];
      if (r >= n_free) continue;
      if (c < n_free) {
        if (r >= c) qff_source_.push_back(p);
      } else {
        qfc_source_.push_back(p);
      }
    }
  }
  if (n_free > 0) ldlt_.analyzePattern(qff_);
}

void GlobalSystem::factorize(const Eigen::SparseMatrix<double>& Q) {
  const double* q = Q.valuePtr();
  for (std::size_t k = 0; k < qff_source_.size(); ++k) qff_.valuePtr()[k] = q[qff_source_[k]];
  for (std::size_t k = 0; k < qfc_source_.size(); ++k) qfc_.valuePtr()[k] = q[qfc_source_[k]];
  if (n_free_ == 0) return;
  ldlt_.factorize(qff_);
  if (ldlt_.info() != Eigen::Success) {
    throw FactorizationError("the global matrix (" + std::to_string(n_free_) +
                             " free vertices) could not be factored: it is not positive definite");
  }
  const Eigen::VectorXd d = ldlt_.vectorD();
  const double largest = d.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(d(i) > 1e-13 * largest)) {
      throw FactorizationError("the global matrix (" + std::to_string(n_free_) +
                               " free vertices) is singular or indefinite (pivot " + std::to_string(i) +
                               " = " + std::to_string(d(i)) + ", largest " + std::to_string(largest) + ")");
    }
  }
  inv_d_ = d.cwiseInverse();
  perm_ = ldlt_.permutationP().indices();
  plan_split();
}

Eigen::Matrix3Xd GlobalSystem::constrained_rhs(const Eigen::Matrix3Xd& X_c) const {
  Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, n_free_);
  for (int c = 0; c < qfc_.outerSize(); ++c) {
    const Eigen::Vector3d x = X_c.col(c);
    for (Eigen::SparseMatrix<double>::InnerIterator it(qfc_, c); it; ++it)
      out.col(it.row()) -= it.value() * x;
  }
  return out;
}

}  // namespace pushpull::deform::detail
