#include "global_system.hpp"

#include <Eigen/SparseCholesky>
#include <cstdio>
#include <stdexcept>
#include <string>

#if PUSHPULL_HAVE_CHOLMOD
#include <cholmod.h>
#else
#define PUSHPULL_HAVE_CHOLMOD 0
#endif

namespace pushpull::deform::detail {
namespace {

std::string not_positive_definite(int n_free) {
  return "the global matrix (" + std::to_string(n_free) +
         " free vertices) could not be factored: it is not positive definite";
}

#if PUSHPULL_HAVE_CHOLMOD
// From this many free vertices on, CHOLMOD with METIS beats Eigen with AMD (deform_bench, 2-core machine):
// at 100K its factor has 14% fewer entries (3.76M vs 4.37M), refactoring takes 200 ms instead of 245 and an
// iteration 31 ms instead of 35, for 250 ms more analysis, once per region; at 30K they are even (analysis
// +60 ms, iterations -5%); at 10K CHOLMOD refactors 1.5 ms slower (8 vs 6.5 ms) with the same iterations.
constexpr int kCholmodMinFree = 50000;

// CHOLMOD's simplicial LDL^T (its supernodal factor is slower here with Debian's reference BLAS, and its
// columns could not be split for two threads) with METIS's nested dissection, whose top separator leaves
// two balanced subtrees for the split solve. METIS is seeded and the numeric factorization sequential, so
// the same Q gives a bit-identical factor. Owns the cholmod_common and the factor (freed in reverse order).
class CholmodFactor {
 public:
  CholmodFactor() {
    cholmod_start(&common_);
    common_.print = 0;  // failures are reported through FactorizationError, not printed
    common_.supernodal = CHOLMOD_SIMPLICIAL;
    common_.final_ll = 0;    // keep LDL^T (no square roots)
    common_.final_asis = 1;  // keep the factor as computed (simplicial)
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_METIS;
    common_.postorder = 1;
  }
  ~CholmodFactor() {
    if (L_) cholmod_free_factor(&L_, &common_);
    cholmod_finish(&common_);
  }
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  // The analysis of `A`, a matrix with the pattern `other` analysed, with `other`'s fill-reducing ordering
  // (no METIS run: the elimination tree and column counts only).
  void analyze_like(Eigen::SparseMatrix<double>& A, const CholmodFactor& other) {
    cholmod_sparse a = view(A);
    common_.method[0].ordering = CHOLMOD_GIVEN;
    L_ = cholmod_analyze_p(&a, static_cast<int*>(other.L_->Perm), nullptr, 0, &common_);
    common_.method[0].ordering = CHOLMOD_METIS;
    if (!L_) {
      throw FactorizationError(
          "the global matrix (" + std::to_string(A.cols()) +
          " free vertices) could not be analysed with a given ordering (CHOLMOD status " +
          std::to_string(common_.status) + ")");
    }
  }

  // Symbolic analysis of the lower triangle `A` (ordering, elimination tree, column counts).
  void analyze(Eigen::SparseMatrix<double>& A) {
    cholmod_sparse a = view(A);
    L_ = cholmod_analyze(&a, &common_);
    if (!L_) {
      throw FactorizationError("the global matrix (" + std::to_string(A.cols()) +
                               " free vertices) could not be analysed (CHOLMOD status " +
                               std::to_string(common_.status) + ")");
    }
  }

  // Numeric LDL^T of `A` (same pattern as analysed), reusing the analysis. Returns the factor: simplicial,
  // packed, D first in each column. Throws FactorizationError on a zero pivot or a CHOLMOD failure.
  const cholmod_factor& factorize(Eigen::SparseMatrix<double>& A) {
    const int n = static_cast<int>(A.cols());
    cholmod_sparse a = view(A);
    const int ok = cholmod_factorize(&a, L_, &common_);
    if (!ok || common_.status < CHOLMOD_OK) {
      throw FactorizationError("the global matrix (" + std::to_string(n) +
                               " free vertices) could not be factored (CHOLMOD status " +
                               std::to_string(common_.status) + ")");
    }
    if (common_.status == CHOLMOD_NOT_POSDEF || L_->minor < L_->n) {
      throw FactorizationError(not_positive_definite(n));
    }
    if (L_->is_super || L_->is_ll || L_->xtype != CHOLMOD_REAL || L_->itype != CHOLMOD_INT) {
      throw std::logic_error("GlobalSystem: CHOLMOD returned an unexpected factor type");
    }
    if (!packed_with_diagonal_first(n)) {
      cholmod_pack_factor(L_, &common_);
      if (!packed_with_diagonal_first(n)) {
        throw std::logic_error("GlobalSystem: CHOLMOD's factor is not packed with D first");
      }
    }
    return *L_;
  }

 private:
  // A view of `A` as CHOLMOD's symmetric lower-stored matrix (no copy; CHOLMOD only reads it).
  static cholmod_sparse view(Eigen::SparseMatrix<double>& A) {
    cholmod_sparse s{};
    s.nrow = static_cast<std::size_t>(A.rows());
    s.ncol = static_cast<std::size_t>(A.cols());
    s.nzmax = static_cast<std::size_t>(A.nonZeros());
    s.p = A.outerIndexPtr();
    s.i = A.innerIndexPtr();
    s.x = A.valuePtr();
    s.stype = -1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }
  bool packed_with_diagonal_first(int n) const {
    const int* p = static_cast<const int*>(L_->p);
    const int* nz = static_cast<const int*>(L_->nz);
    const int* i = static_cast<const int*>(L_->i);
    for (int j = 0; j < n; ++j) {
      if (nz[j] != p[j + 1] - p[j] || i[p[j]] != j) return false;
    }
    return true;
  }

  cholmod_common common_{};
  cholmod_factor* L_ = nullptr;  // symbolic after analyze, numeric LDL^T after factorize
};
#endif

}  // namespace

// Eigen's SimplicialLDLT with AMD, or (large regions, CHOLMOD built in) CHOLMOD's: one of the two is used.
struct GlobalSystem::Factor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> eigen;
#if PUSHPULL_HAVE_CHOLMOD
  std::unique_ptr<CholmodFactor> cholmod;
#endif
};

bool GlobalSystem::cholmod_available() { return PUSHPULL_HAVE_CHOLMOD != 0; }

void GlobalSystem::analyze_factor(Backend backend) {
  factor_ = std::make_unique<Factor>();
#if PUSHPULL_HAVE_CHOLMOD
  if (backend == Backend::Cholmod || (backend == Backend::Automatic && n_free_ >= kCholmodMinFree)) {
    factor_->cholmod = std::make_unique<CholmodFactor>();
    factor_->cholmod->analyze(qff_);
    return;
  }
#else
  (void)backend;
#endif
  factor_->eigen.analyzePattern(qff_);
}

void GlobalSystem::analyze_like(const GlobalSystem& analysed) {
  n_free_ = analysed.n_free_;
  qff_ = analysed.qff_;
  qfc_ = analysed.qfc_;
  qff_source_ = analysed.qff_source_;
  qfc_source_ = analysed.qfc_source_;
  l_column_ = l_row_ = nullptr;
  l_value_ = nullptr;
  factor_.reset();
  if (n_free_ == 0) return;
  if (!analysed.factor_)
    throw std::logic_error("GlobalSystem::analyze_like: the system given is not analysed");
  factor_ = std::make_unique<Factor>();
#if PUSHPULL_HAVE_CHOLMOD
  if (analysed.factor_->cholmod) {
    factor_->cholmod = std::make_unique<CholmodFactor>();
    factor_->cholmod->analyze_like(qff_, *analysed.factor_->cholmod);
    return;
  }
#endif
  factor_->eigen.analyzePattern(qff_);  // AMD on the regions Eigen factors is cheap beside the factorization
}

void GlobalSystem::factor_numeric() {
  const int n = n_free_;
#if PUSHPULL_HAVE_CHOLMOD
  if (factor_->cholmod) {
    const cholmod_factor& L = factor_->cholmod->factorize(qff_);
    l_column_ = static_cast<const int*>(L.p);
    l_row_ = static_cast<const int*>(L.i);
    l_value_ = static_cast<const double*>(L.x);
    l_diagonal_slots_ = 1;
    d_.resize(n);
    for (int j = 0; j < n; ++j) d_(j) = l_value_[l_column_[j]];
    const int* order = static_cast<const int*>(L.Perm);  // row k of P Q P^T is row order[k] of Q
    perm_.resize(n);
    for (int k = 0; k < n; ++k) perm_(order[k]) = k;
    return;
  }
#endif
  auto& ldlt = factor_->eigen;
  ldlt.factorize(qff_);
  if (ldlt.info() != Eigen::Success) throw FactorizationError(not_positive_definite(n));
  const Eigen::SparseMatrix<double>& L = ldlt.matrixL().nestedExpression();  // strictly lower
  l_column_ = L.outerIndexPtr();
  l_row_ = L.innerIndexPtr();
  l_value_ = L.valuePtr();
  l_diagonal_slots_ = 0;
  d_ = ldlt.vectorD();
  perm_ = ldlt.permutationP().indices();
}

GlobalSystem::GlobalSystem() = default;
GlobalSystem::~GlobalSystem() = default;
GlobalSystem::GlobalSystem(GlobalSystem&&) noexcept = default;
GlobalSystem& GlobalSystem::operator=(GlobalSystem&&) noexcept = default;

void GlobalSystem::analyze(const Eigen::SparseMatrix<double>& Q, int n_free, Backend backend) {
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
  l_column_ = l_row_ = nullptr;
  l_value_ = nullptr;
  factor_.reset();
  if (n_free > 0) analyze_factor(backend);
}

void GlobalSystem::factorize(const Eigen::SparseMatrix<double>& Q) {
  const double* q = Q.valuePtr();
  for (std::size_t k = 0; k < qff_source_.size(); ++k) qff_.valuePtr()[k] = q[qff_source_[k]];
  for (std::size_t k = 0; k < qfc_source_.size(); ++k) qfc_.valuePtr()[k] = q[qfc_source_[k]];
  if (n_free_ == 0) return;
  factor_numeric();
  const Eigen::VectorXd& d = d_;
  const double largest = d.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(d(i) > 1e-13 * largest)) {
      char values[64];  // (%.3g: std::to_string wrote 300 digits for 1e300 and 0.000000 for 4e-9)
      std::snprintf(values, sizeof values, " = %.3g, largest %.3g)", d(i), largest);
      throw FactorizationError("the global matrix (" + std::to_string(n_free_) +
                               " free vertices) is singular or indefinite (pivot " + std::to_string(i) +
                               values);
    }
  }
  inv_d_ = d.cwiseInverse();
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
