// The local-global iterations (Sorkine & Alexa 2007) shared by every method, with optional Anderson
// acceleration (Peng et al. 2018) guarded by the energy.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "deformer_impl.hpp"
#include "rotation.hpp"

namespace pushpull::deform {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// tr(X Q X^T) for Q symmetric with both triangles stored, over the block of rows and columns >= first_column.
double quadratic_form(const Eigen::SparseMatrix<double>& Q, const Eigen::Matrix3Xd& X, int first_column = 0) {
  double sum = 0.0;
  for (int j = first_column; j < Q.outerSize(); ++j) {
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (int p = Q.outerIndexPtr()[j]; p < Q.outerIndexPtr()[j + 1]; ++p) {
      if (Q.innerIndexPtr()[p] >= first_column) acc += Q.valuePtr()[p] * X.col(Q.innerIndexPtr()[p]);
    }
    sum += acc.dot(X.col(j));
  }
  return sum;
}

}  // namespace

double Deformer::Impl::local_step(const Eigen::Matrix3Xd& X, std::vector<Eigen::Matrix3d>& R,
                                  std::vector<Eigen::Quaterniond>& q, bool R_valid, int sweeps,
                                  std::optional<double> known_quadratic, Eigen::Matrix3Xd* rhs) const {
  const detail::EnergyModel& m = model;
  const int clusters = m.cluster_count;
  const bool smooth = m.smooth_scale > 0.0;
  const int* start = m.cluster_start.data();
  const int* vertex = m.term_vertex.data();
  const double* g = m.term_g.data();
  const double* x = X.data();
  double* b = nullptr;
  if (rhs) {
    rhs->setZero(3, n_free);
    b = rhs->data();
  }
  // B_f += R_c g_t over the free vertices of cluster c's terms (ascending t, as a separate pass would).
  auto scatter = [&](int c, const Eigen::Matrix3d& Rc) {
    for (int t = start[c]; t < start[c + 1]; ++t) {
      const int v = vertex[t];
      if (v >= n_free) continue;
      const double g0 = g[3 * t], g1 = g[3 * t + 1], g2 = g[3 * t + 2];
      double* bv = b + 3 * v;
      bv[0] += Rc(0, 0) * g0 + Rc(0, 1) * g1 + Rc(0, 2) * g2;
      bv[1] += Rc(1, 0) * g0 + Rc(1, 1) * g1 + Rc(1, 2) * g2;
      bv[2] += Rc(2, 0) * g0 + Rc(2, 1) * g1 + Rc(2, 2) * g2;
    }
  };
  // Warm rotations take one Newton step unless it is long (see closest_rotation); cold ones converge fully.
  const double accept = R_valid ? 1e-2 : 1e-4;
  std::vector<Eigen::Matrix3d> covariance;
  if (smooth) covariance.resize(static_cast<std::size_t>(clusters));
  double coupling = 0.0;  // sum_c R_c : A_c
  for (int c = 0; c < clusters; ++c) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    for (int t = start[c]; t < start[c + 1]; ++t) {
      const double* xv = x + 3 * vertex[t];
      const double* gt = g + 3 * t;
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) A(i, j) += xv[i] * gt[j];
      }
    }
    Eigen::Matrix3d& Rc = R[static_cast<std::size_t>(c)];
    if (smooth) {
      covariance[static_cast<std::size_t>(c)] = A;
      if (!R_valid) Rc = detail::closest_rotation(A, q[static_cast<std::size_t>(c)], 20, accept);
    } else {
      Rc = detail::closest_rotation(A, q[static_cast<std::size_t>(c)], 20, accept);
      coupling += (Rc.array() * A.array()).sum();
      if (b) scatter(c, Rc);
    }
  }
  double smoothing = 0.0;
  if (smooth) {
    // sr-arap: one Gauss-Seidel sweep, each R_k optimal given its neighbours' latest rotations (so the
    // energy cannot rise).
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      for (int c = 0; c < clusters; ++c) {
        Eigen::Matrix3d A = covariance[static_cast<std::size_t>(c)];
        for (int k = m.smooth_start[static_cast<std::size_t>(c)];
             k < m.smooth_start[static_cast<std::size_t>(c) + 1]; ++k) {
          A += m.smooth_scale * m.smooth_weight[static_cast<std::size_t>(k)] *
               R[static_cast<std::size_t>(m.smooth_cluster[static_cast<std::size_t>(k)])];
        }
        R[static_cast<std::size_t>(c)] =
            detail::closest_rotation(A, q[static_cast<std::size_t>(c)], 20, accept);
      }
    }
    for (int c = 0; c < clusters; ++c) {
      coupling +=
          (R[static_cast<std::size_t>(c)].array() * covariance[static_cast<std::size_t>(c)].array()).sum();
      if (b) scatter(c, R[static_cast<std::size_t>(c)]);
      for (int k = m.smooth_start[static_cast<std::size_t>(c)];
           k < m.smooth_start[static_cast<std::size_t>(c) + 1]; ++k) {
        const int d = m.smooth_cluster[static_cast<std::size_t>(k)];
        if (d < c) continue;  // each edge once
        smoothing +=
            m.smooth_weight[static_cast<std::size_t>(k)] *
            (6.0 -
             2.0 * (R[static_cast<std::size_t>(c)].array() * R[static_cast<std::size_t>(d)].array()).sum());
      }
    }
    smoothing *= m.smooth_scale;
  }
  // tr(X Q X^T), Q symmetric with both triangles stored.
  const double quadratic = known_quadratic ? *known_quadratic : quadratic_form(m.Q, X);
  return quadratic - 2.0 * coupling + m.constant + smoothing;
}

void Deformer::Impl::global_step(const Eigen::Matrix3Xd& B, const Eigen::Matrix3Xd& rhs_c,
                                 double constrained_quadratic, Eigen::Matrix3Xd& G, double& quadratic) const {
  G.resize(3, n_free);
  G.noalias() = B + rhs_c;
  system.solve_in_place(G);
  const double* xf = G.data();
  const double* bf = B.data();
  const double* rc = rhs_c.data();
  double sum = 0.0;
  for (Eigen::Index k = 0; k < G.size(); ++k) sum += xf[k] * (bf[k] - rc[k]);
  quadratic = sum + constrained_quadratic;
}

DeformResult Deformer::Impl::run(const Eigen::Matrix3Xd& X_c, const Eigen::Vector3d& push_direction,
                                 const Eigen::MatrixXd& initial_guess) {
  DeformResult result;
  result.warnings = setup_warnings;
  result.timing.precompute = precompute_ms;
  result.timing.factorize = prepare_weights(push_direction, result.warnings);
  const auto solve_start = Clock::now();

  const int n = static_cast<int>(P.cols());
  Eigen::Matrix3Xd X = P;
  if (initial_guess.size() != 0) {
    for (int i = 0; i < n_free; ++i)
      X.col(i) = initial_guess.row(local_to_global[static_cast<std::size_t>(i)]).transpose();
  }
  X.rightCols(n - n_free) = X_c;

  // Reference length for the move tolerance: the largest prescribed displacement, else the region's size.
  double reference = (X_c - P.rightCols(n - n_free)).colwise().norm().maxCoeff();
  if (!(reference > 0.0)) reference = (P.rowwise().maxCoeff() - P.rowwise().minCoeff()).norm();
  if (!(reference > 0.0)) reference = 1.0;

  const Eigen::Matrix3Xd rhs_c = system.constrained_rhs(X_c);
  const double constrained_quadratic = quadratic_form(model.Q, X, n_free);  // X_c : Q_cc X_c
  std::vector<Eigen::Matrix3d> R(static_cast<std::size_t>(model.cluster_count), Eigen::Matrix3d::Identity());
  std::vector<Eigen::Quaterniond> q(R.size(), Eigen::Quaterniond::Identity());
  Eigen::Matrix3Xd B(3, n_free), G(3, n_free);  // B_f(R) for the current R; the plain global step
  double energy = local_step(X, R, q, /*R_valid=*/false, 1, std::nullopt, &B);
  result.initial_energy = energy;
  std::optional<detail::Anderson> anderson;
  if (options.anderson_window > 0 && n_free > 0) anderson.emplace(options.anderson_window, 3 * n_free);
  Eigen::MatrixXd preview;

  result.stop_reason = StopReason::MaxIterations;
  for (int iteration = 1; iteration <= options.max_iterations && n_free > 0; ++iteration) {
    double plain_quadratic = 0.0;
    global_step(B, rhs_c, constrained_quadratic, G, plain_quadratic);
    Eigen::Matrix3Xd X_next = X;
    bool accelerated = false;
    if (anderson) {
      const Eigen::VectorXd x_vec = Eigen::Map<const Eigen::VectorXd>(X.data(), 3 * n_free);
      const Eigen::VectorXd g_vec = Eigen::Map<const Eigen::VectorXd>(G.data(), 3 * n_free);
      const Eigen::VectorXd next = anderson->step(x_vec, g_vec);
      accelerated = !next.isApprox(g_vec, 0.0) && next.allFinite();
      X_next.leftCols(n_free) = accelerated ? Eigen::Map<const Eigen::Matrix3Xd>(next.data(), 3, n_free) : G;
    } else {
      X_next.leftCols(n_free) = G;
    }
    // R only warm-starts the next local step (R is a function of X), so it is updated in place.
    double next_energy = accelerated ? local_step(X_next, R, q, true, 1, std::nullopt, &B)
                                     : local_step(X_next, R, q, true, 1, plain_quadratic, &B);
    if (accelerated && !(next_energy <= energy)) {  // safeguard: take the plain (monotone) step
      X_next.leftCols(n_free) = G;
      next_energy = local_step(X_next, R, q, true, 1, plain_quadratic, &B);
      anderson->reset();
    }
    // The plain step's move (the fixed-point residual), also with Anderson, whose iterate differences can
    // stall before convergence.
    const double move = (G - X.leftCols(n_free)).colwise().norm().maxCoeff() / reference;
    X = std::move(X_next);
    result.energy_trace.push_back(next_energy);
    result.iterations = iteration;
    const double previous_energy = energy;
    energy = next_energy;

    if (options.progress) {
      preview = to_full(X);
      const IterationReport report{iteration, energy, move, &preview};
      if (!options.progress(report)) {
        result.cancelled = true;
        result.stop_reason = StopReason::Cancelled;
        break;
      }
    }
    if (options.tolerance > 0.0 && move <= options.tolerance) {
      result.stop_reason = StopReason::MoveTolerance;
      break;
    }
    if (options.energy_tolerance > 0.0 &&
        std::abs(previous_energy - energy) <= options.energy_tolerance * std::abs(previous_energy)) {
      result.stop_reason = StopReason::EnergyTolerance;
      break;
    }
  }
  if (n_free == 0) result.stop_reason = StopReason::MoveTolerance;  // nothing to solve for
  result.converged =
      result.stop_reason == StopReason::MoveTolerance || result.stop_reason == StopReason::EnergyTolerance;
  result.V = to_full(X);
  result.timing.solve = ms_since(solve_start);
  result.timing.per_iteration = result.iterations > 0 ? result.timing.solve / result.iterations : 0.0;
  if (!result.V.allFinite()) {
    throw std::runtime_error("deformer: the solve produced non-finite positions (please report this mesh)");
  }
  return result;
}

}  // namespace pushpull::deform
