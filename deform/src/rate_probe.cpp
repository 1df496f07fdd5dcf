#include "rate_probe.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>

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

RateProbe probe_rate(Eigen::Index dimension, int steps,
                     const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& jacobian,
                     const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& metric) {
  RateProbe probe;
  if (dimension <= 0 || steps <= 0) return probe;
  steps = static_cast<int>(std::min<Eigen::Index>(steps, dimension));
  // V: an M-orthonormal basis of the Krylov space, MV = M V; H: J projected on it (upper Hessenberg).
  Eigen::MatrixXd V(dimension, steps + 1), MV(dimension, steps + 1);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(steps + 1, steps);
  Eigen::VectorXd w(dimension), mw(dimension);
  V.col(0) = probe_start(dimension);
  metric(V.col(0), mw);
  const double start_norm = std::sqrt(std::max(0.0, V.col(0).dot(mw)));
  if (!(start_norm > 0.0) || !std::isfinite(start_norm)) return probe;
  V.col(0) /= start_norm;
  MV.col(0) = mw / start_norm;
  int built = 0;
  for (int j = 0; j < steps; ++j) {
    jacobian(V.col(j), w);
    ++probe.evaluations;
    if (!w.allFinite()) break;
    // Classical Gram-Schmidt in the M inner product, twice (the second pass mends the first's cancellation).
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd c = MV.leftCols(j + 1).transpose() * w;
      w.noalias() -= V.leftCols(j + 1) * c;
      H.col(j).head(j + 1) += c;
    }
    built = j + 1;
    metric(w, mw);
    const double next = std::sqrt(std::max(0.0, w.dot(mw)));
    H(j + 1, j) = next;
    if (!std::isfinite(next) || !(next > 1e-12 * std::max(1.0, H.col(j).head(j + 1).norm()))) break;
    V.col(j + 1) = w / next;
    MV.col(j + 1) = mw / next;
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

}  // namespace pushpull::deform::detail
