#include "rate_probe.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pushpull::deform::detail {

Eigen::VectorXd probe_start(Eigen::Index dimension) {
  Eigen::VectorXd v(dimension);
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (Eigen::Index k = 0; k < dimension; ++k) {
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    v[k] = static_cast<double>(z >> 11) * 0x1.0p-53 - 0.5;
  }
  const double norm = v.norm();
  if (norm > 0.0) v /= norm;
  return v;
}

namespace {

// The start vector: the fixed random one, plus, when given, the hint, each scaled to unit M norm (the caller
// normalises the sum).
Eigen::VectorXd start_vector(Eigen::Index dimension, const Eigen::VectorXd* hint,
                             const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& metric) {
  Eigen::VectorXd v = probe_start(dimension);
  if (hint == nullptr || hint->size() != dimension || !hint->allFinite()) return v;
  Eigen::VectorXd m(dimension);
  metric(v, m);
  const double v_norm = std::sqrt(std::max(0.0, v.dot(m)));
  metric(*hint, m);
  const double h_norm = std::sqrt(std::max(0.0, hint->dot(m)));
  if (!(v_norm > 0.0) || !(h_norm > 0.0) || !std::isfinite(h_norm)) return v;
  return v / v_norm + *hint / h_norm;
}

// One classical Gram-Schmidt pass in the M inner product against the k basis columns of V: c = V^T (M w),
// w -= V c, h += c. The rows are split in two fixed halves (one per thread when given one); the halves'
// partial sums of c are added in a fixed order, so the bits do not depend on the thread count.
void orthogonalise(const Eigen::MatrixXd& V, int k, const Eigen::VectorXd& mw, Eigen::VectorXd& w,
                   Eigen::Ref<Eigen::VectorXd> h, HelperThread* threads) {
  const Eigen::Index n = V.rows();
  std::array<Eigen::VectorXd, 2> partial;
  auto project = [&](int part) {
    const Eigen::Index begin = half_begin(part, n), length = half_end(part, n) - begin;
    partial[static_cast<std::size_t>(part)].noalias() =
        V.block(begin, 0, length, k).transpose() * mw.segment(begin, length);
  };
  run_halves(threads, project);
  const Eigen::VectorXd c = partial[0] + partial[1];
  auto update = [&](int part) {
    const Eigen::Index begin = half_begin(part, n), length = half_end(part, n) - begin;
    w.segment(begin, length).noalias() -= V.block(begin, 0, length, k) * c;
  };
  run_halves(threads, update);
  h += c;
}

}  // namespace

RateProbe probe_rate(Eigen::Index dimension, int steps,
                     const std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&)>& jacobian,
                     const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& metric,
                     HelperThread* threads, const Eigen::VectorXd* hint) {
  RateProbe probe;
  if (dimension <= 0 || steps <= 0) return probe;
  steps = static_cast<int>(std::min<Eigen::Index>(steps, dimension));
  // V: an M-orthonormal basis of the Krylov space; H: J projected on it (upper Hessenberg).
  Eigen::MatrixXd V(dimension, steps);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(steps + 1, steps);
  Eigen::VectorXd v = start_vector(dimension, hint, metric), w(dimension), mw(dimension);
  metric(v, mw);
  const double start_norm = std::sqrt(std::max(0.0, v.dot(mw)));
  if (!(start_norm > 0.0) || !std::isfinite(start_norm)) return probe;
  V.col(0) = v / start_norm;
  int built = 0;
  for (int j = 0; j < steps; ++j) {
    v = V.col(j);
    if (!jacobian(v, w)) {
      probe.abandoned = true;
      return probe;
    }
    ++probe.evaluations;
    if (!w.allFinite()) break;
    // Classical Gram-Schmidt in the M inner product, twice (the second pass mends the first's
    // cancellation; Daniel, Gragg, Kaufman and Stewart's test, a second pass only where the first left less
    // than 1/sqrt(2) of w, asked for it at 39 of 40 steps in a scratch count on the 10K height field, not in
    // the tree: J v lies mostly in the Krylov space already).
    for (int pass = 0; pass < 2; ++pass) {
      metric(w, mw);
      orthogonalise(V, j + 1, mw, w, H.col(j).head(j + 1), threads);
    }
    built = j + 1;
    if (j + 1 == steps) break;
    metric(w, mw);
    const double next = std::sqrt(std::max(0.0, w.dot(mw)));
    if (!std::isfinite(next) || !(next > 1e-12 * std::max(1.0, H.col(j).head(j + 1).norm()))) break;
    H(j + 1, j) = next;
    V.col(j + 1) = w / next;
  }
  if (built == 0) return probe;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(H.topLeftCorner(built, built),
                                                  /*computeEigenvectors=*/false);
  if (eigen.info() != Eigen::Success) return probe;
  for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k) {
    const double magnitude = std::abs(eigen.eigenvalues()(k));
    if (std::isfinite(magnitude)) probe.rate = std::max(probe.rate, magnitude);
  }
  return probe;
}

RateProbe probe_rate_self_adjoint(
    Eigen::Index dimension, int steps,
    const std::function<bool(const Eigen::VectorXd&, Eigen::VectorXd&)>& jacobian,
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& metric,
    const Eigen::VectorXd* hint) {
  RateProbe probe;
  if (dimension <= 0 || steps <= 0) return probe;
  steps = static_cast<int>(std::min<Eigen::Index>(steps, dimension));
  // v, mv: the current basis vector and M v; previous, m_previous: the one before (zero at the start).
  Eigen::VectorXd v = start_vector(dimension, hint, metric), mv(dimension), w(dimension), mw(dimension);
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(dimension), m_previous = Eigen::VectorXd::Zero(dimension);
  metric(v, mv);
  const double start_norm = std::sqrt(std::max(0.0, v.dot(mv)));
  if (!(start_norm > 0.0) || !std::isfinite(start_norm)) return probe;
  v /= start_norm;
  mv /= start_norm;
  std::vector<double> diagonal, off_diagonal;  // the tridiagonal projection of J
  for (int j = 0; j < steps; ++j) {
    if (!jacobian(v, w)) {
      probe.abandoned = true;
      return probe;
    }
    ++probe.evaluations;
    if (!w.allFinite()) break;
    // Against v and the previous vector, twice (the second pass mends the first's cancellation, as
    // probe_rate's second Gram-Schmidt pass does).
    double alpha = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      const double along = w.dot(mv);
      w -= along * v;
      alpha += along;
      if (j > 0) w -= w.dot(m_previous) * previous;
    }
    diagonal.push_back(alpha);
    if (j + 1 == steps) break;
    metric(w, mw);
    const double next = std::sqrt(std::max(0.0, w.dot(mw)));
    if (!std::isfinite(next) || !(next > 1e-12 * std::max(1.0, std::abs(alpha)))) break;
    off_diagonal.push_back(next);
    previous.swap(v);
    m_previous.swap(mv);
    v = w / next;
    mv = mw / next;
  }
  const auto built = static_cast<Eigen::Index>(diagonal.size());
  if (built == 0) return probe;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(built, built);
  for (Eigen::Index k = 0; k < built; ++k) {
    T(k, k) = diagonal[static_cast<std::size_t>(k)];
    if (k + 1 < built) T(k + 1, k) = T(k, k + 1) = off_diagonal[static_cast<std::size_t>(k)];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(T, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success || !eigen.eigenvalues().allFinite()) return probe;
  probe.rate = eigen.eigenvalues().cwiseAbs().maxCoeff();
  return probe;
}

}  // namespace pushpull::deform::detail
