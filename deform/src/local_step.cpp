// The local step of the local-global solver: per-cluster covariances and optimal rotations, the energy, and
// the next global step's right-hand side, in two fixed parts that may run on two threads.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "deformer_impl.hpp"
#include "rotation.hpp"
#include "rotation_batch.hpp"

namespace pushpull::deform {
namespace {

// Columns [j0, j1) of tr(X Q X^T) for Q symmetric with both triangles stored.
double quadratic_columns(const Eigen::SparseMatrix<double>& Q, const Eigen::Matrix3Xd& X, int j0, int j1) {
  const int* outer = Q.outerIndexPtr();
  const int* inner = Q.innerIndexPtr();
  const double* value = Q.valuePtr();
  const double* x = X.data();
  double sum = 0.0;
  for (int j = j0; j < j1; ++j) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int p = outer[j]; p < outer[j + 1]; ++p) {
      const double* xi = x + 3 * static_cast<std::ptrdiff_t>(inner[p]);
      a0 += value[p] * xi[0];
      a1 += value[p] * xi[1];
      a2 += value[p] * xi[2];
    }
    const double* xj = x + 3 * static_cast<std::ptrdiff_t>(j);
    sum += a0 * xj[0] + a1 * xj[1] + a2 * xj[2];
  }
  return sum;
}

// Covariance A_c = sum_t x_vertex(t) g_t^T over the terms [t0, t1) of one cluster.
Eigen::Matrix3d covariance(const double* x, const double* g, const int* vertex, int t0, int t1) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  for (int t = t0; t < t1; ++t) {
    const double* xv = x + 3 * static_cast<std::ptrdiff_t>(vertex[t]);
    const double* gt = g + 3 * static_cast<std::ptrdiff_t>(t);
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) A(i, j) += xv[i] * gt[j];
    }
  }
  return A;
}

// b += R g.
inline void add_rotated(double* b, const Eigen::Matrix3d& R, const double* g) {
  b[0] += R(0, 0) * g[0] + R(0, 1) * g[1] + R(0, 2) * g[2];
  b[1] += R(1, 0) * g[0] + R(1, 1) * g[1] + R(1, 2) * g[2];
  b[2] += R(2, 0) * g[0] + R(2, 1) * g[1] + R(2, 2) * g[2];
}

}  // namespace

void Deformer::Impl::plan_local_split() {
  const detail::EnergyModel& m = model;
  const int clusters = m.cluster_count;
  const int total = m.cluster_start.back();
  // Balance the parts by term count (covariance and right-hand-side work are per term).
  split_cluster = static_cast<int>(
      std::lower_bound(m.cluster_start.begin(), m.cluster_start.end(), total / 2) - m.cluster_start.begin());
  split_cluster = std::clamp(split_cluster, 0, clusters);
  std::vector<char> in_part0(static_cast<std::size_t>(n_free), 0);
  for (int t = 0; t < m.cluster_start[static_cast<std::size_t>(split_cluster)]; ++t) {
    const int v = m.term_vertex[static_cast<std::size_t>(t)];
    if (v < n_free) in_part0[static_cast<std::size_t>(v)] = 1;
  }
  shared_slot.assign(static_cast<std::size_t>(n_free), -1);
  shared_vertex.clear();
  for (int t = m.cluster_start[static_cast<std::size_t>(split_cluster)]; t < total; ++t) {
    const int v = m.term_vertex[static_cast<std::size_t>(t)];
    if (v < n_free && in_part0[static_cast<std::size_t>(v)] && shared_slot[static_cast<std::size_t>(v)] < 0) {
      shared_slot[static_cast<std::size_t>(v)] = static_cast<int>(shared_vertex.size());
      shared_vertex.push_back(v);
    }
  }
}

double Deformer::Impl::local_step(const Eigen::Matrix3Xd& X, std::vector<Eigen::Matrix3d>& R,
                                  std::vector<Eigen::Quaterniond>& q, bool R_valid, int sweeps,
                                  std::optional<double> known_quadratic, Eigen::Matrix3Xd* rhs,
                                  detail::HelperThread* threads, double sweep_tolerance) const {
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
  // Warm rotations take one Newton step unless it is long (see closest_rotation); cold ones converge fully.
  const double accept = R_valid ? 1e-2 : 1e-4;
  const int n = static_cast<int>(X.cols());
  const bool need_quadratic = !known_quadratic.has_value();

  if (!smooth) {
    // Part p: clusters [c0, c1) (rotations, coupling sum_c R_c : A_c, right-hand side) and columns [j0, j1)
    // of the quadratic form. Each part writes its own clusters' R and q, its own sums, and right-hand-side
    // columns no other part writes (part 1 puts shared vertices' contributions in `shared`).
    std::vector<double> shared(b ? 3 * shared_vertex.size() : 0, 0.0);
    std::array<double, 2> coupling{0.0, 0.0}, quadratic{0.0, 0.0};
    auto part = [&](int p) {
      const int c0 = p == 0 ? 0 : split_cluster, c1 = p == 0 ? split_cluster : clusters;
      double sum = 0.0;
      // Cluster c's share of the coupling and of the right-hand side, once R_c is known.
      auto finish = [&](int c, const Eigen::Matrix3d& A, const Eigen::Matrix3d& Rc) {
        sum += (Rc.array() * A.array()).sum();
        if (!b) return;
        for (int t = start[c]; t < start[c + 1]; ++t) {
          const int v = vertex[t];
          if (v >= n_free) continue;
          const int slot = p == 0 ? -1 : shared_slot[static_cast<std::size_t>(v)];
          double* target = slot < 0 ? b + 3 * static_cast<std::ptrdiff_t>(v) : shared.data() + 3 * slot;
          add_rotated(target, Rc, g + 3 * static_cast<std::ptrdiff_t>(t));
        }
      };
      // Polar rotations kRotationLanes clusters at a time: the first step of closest_rotation for all of
      // them at once (rotation_batch.hpp); a cluster that needs more goes on alone from there.
      constexpr int kLanes = detail::kRotationLanes;
      const int batched_end = std::min(c1, m.rank_one_begin);
      detail::RotationLanes lanes;
      std::array<Eigen::Matrix3d, kLanes> A;
      for (int c = c0; c < batched_end; c += kLanes) {
        const int count = std::min(kLanes, batched_end - c);
        for (int l = 0; l < kLanes; ++l) {
          if (l < count) {
            A[static_cast<std::size_t>(l)] = covariance(x, g, vertex, start[c + l], start[c + l + 1]);
          } else {
            A[static_cast<std::size_t>(l)].setIdentity();
          }
          const Eigen::Quaterniond& ql =
              l < count ? q[static_cast<std::size_t>(c + l)] : Eigen::Quaterniond::Identity();
          for (int k = 0; k < 9; ++k) lanes.a[k][l] = A[static_cast<std::size_t>(l)](k / 3, k % 3);
          for (int k = 0; k < 4; ++k) lanes.q[k][l] = ql.coeffs()[k];  // x, y, z, w
        }
        const std::uint32_t finished = detail::closest_rotation_step(lanes, accept);
        for (int l = 0; l < count; ++l) {
          Eigen::Quaterniond& qc = q[static_cast<std::size_t>(c + l)];
          for (int k = 0; k < 4; ++k) qc.coeffs()[k] = lanes.q[k][l];
          Eigen::Matrix3d& Rc = R[static_cast<std::size_t>(c + l)];
          if ((finished >> l) & 1u) {
            for (int k = 0; k < 9; ++k) Rc(k / 3, k % 3) = lanes.r[k][l];
          } else {
            Rc = detail::closest_rotation(A[static_cast<std::size_t>(l)], qc, 19, accept);
          }
          finish(c + l, A[static_cast<std::size_t>(l)], Rc);
        }
      }
      for (int c = std::max(c0, batched_end); c < c1; ++c) {  // arap-h's rank-one bending clusters
        const Eigen::Matrix3d Ac = covariance(x, g, vertex, start[c], start[c + 1]);
        Eigen::Matrix3d& Rc = R[static_cast<std::size_t>(c)];
        Rc = detail::rotation_onto(Ac, m.rank_one_axis.col(c - m.rank_one_begin),
                                   q[static_cast<std::size_t>(c)]);
        finish(c, Ac, Rc);
      }
      coupling[static_cast<std::size_t>(p)] = sum;
      if (need_quadratic) {
        const int half = n / 2;
        quadratic[static_cast<std::size_t>(p)] =
            quadratic_columns(m.Q, X, p == 0 ? 0 : half, p == 0 ? half : n);
      }
    };
    detail::run_halves(threads, part);
    for (std::size_t s = 0; s < shared_vertex.size() && b; ++s) {
      double* bv = b + 3 * static_cast<std::ptrdiff_t>(shared_vertex[s]);
      for (int i = 0; i < 3; ++i) bv[i] += shared[3 * s + static_cast<std::size_t>(i)];
    }
    const double quad = need_quadratic ? quadratic[0] + quadratic[1] : *known_quadratic;
    return quad - 2.0 * (coupling[0] + coupling[1]) + m.constant;
  }

  // sr-arap: covariances, then Gauss-Seidel sweeps over the rotations (sequential by nature).
  std::vector<Eigen::Matrix3d> covariances(static_cast<std::size_t>(clusters));
  for (int c = 0; c < clusters; ++c) {
    covariances[static_cast<std::size_t>(c)] = covariance(x, g, vertex, start[c], start[c + 1]);
    if (!R_valid)
      R[static_cast<std::size_t>(c)] = detail::closest_rotation(covariances[static_cast<std::size_t>(c)],
                                                                q[static_cast<std::size_t>(c)], 20, accept);
  }
  // Each R_k optimal given its neighbours' latest rotations (so the energy cannot rise).
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    double largest_change = 0.0;
    for (int c = 0; c < clusters; ++c) {
      Eigen::Matrix3d A = covariances[static_cast<std::size_t>(c)];
      for (int k = m.smooth_start[static_cast<std::size_t>(c)];
           k < m.smooth_start[static_cast<std::size_t>(c) + 1]; ++k) {
        A += m.smooth_scale * m.smooth_weight[static_cast<std::size_t>(k)] *
             R[static_cast<std::size_t>(m.smooth_cluster[static_cast<std::size_t>(k)])];
      }
      const Eigen::Matrix3d next = detail::closest_rotation(A, q[static_cast<std::size_t>(c)], 20, accept);
      largest_change =
          std::max(largest_change, (next - R[static_cast<std::size_t>(c)]).cwiseAbs().maxCoeff());
      R[static_cast<std::size_t>(c)] = next;
    }
    if (sweep_tolerance > 0.0 && largest_change <= sweep_tolerance) break;
  }
  double coupling = 0.0, smoothing = 0.0;
  for (int c = 0; c < clusters; ++c) {
    const Eigen::Matrix3d& Rc = R[static_cast<std::size_t>(c)];
    coupling += (Rc.array() * covariances[static_cast<std::size_t>(c)].array()).sum();
    if (b) {
      for (int t = start[c]; t < start[c + 1]; ++t) {
        if (vertex[t] < n_free)
          add_rotated(b + 3 * static_cast<std::ptrdiff_t>(vertex[t]), Rc,
                      g + 3 * static_cast<std::ptrdiff_t>(t));
      }
    }
    for (int k = m.smooth_start[static_cast<std::size_t>(c)];
         k < m.smooth_start[static_cast<std::size_t>(c) + 1]; ++k) {
      const int d = m.smooth_cluster[static_cast<std::size_t>(k)];
      if (d < c) continue;  // each edge once
      smoothing += m.smooth_weight[static_cast<std::size_t>(k)] *
                   (6.0 - 2.0 * (Rc.array() * R[static_cast<std::size_t>(d)].array()).sum());
    }
  }
  smoothing *= m.smooth_scale;
  const double quad = need_quadratic ? quadratic_columns(m.Q, X, 0, n) : *known_quadratic;
  return quad - 2.0 * coupling + m.constant + smoothing;
}

}  // namespace pushpull::deform
