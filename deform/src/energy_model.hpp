// Private: the "rotation cluster" form shared by every energy of the ARAP family.
//
//   E(X, R) = tr(X Q X^T) - 2 sum_c R_c : A_c(X) + C + smooth_scale * sum_{(c,d)} w_cd (6 - 2 R_c : R_d)
//   A_c(X)  = sum_{t in terms(c)} x_{vertex(t)} g_t^T            (3x3 "covariance", R_c = polar(A_c))
//   b_v(R)  = sum_{t : vertex(t) = v} R_{cluster(t)} g_t          (right-hand side of the global step)
// X is 3 by n (local vertices, free ones first), Q n by n symmetric positive semidefinite. A weighted edge
// (i, j, w) of cluster c contributes w e_ij to g of (c,i), -w e_ij to g of (c,j), w to Q_ii and Q_jj, -w to
// Q_ij and Q_ji, and w |e_ij|^2 to C, with e_ij = p_i - p_j at rest. Weights are "slots": half cotangents
// of (face, corner), so changing them (ASAN) refills numbers without touching any pattern.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "pushpull/deform/method.hpp"

namespace pushpull::deform::detail {

struct ModelSpec {
  Method structure = Method::ArapSR;  // ArapS, ArapSR, ArapM or ArapN: how clusters are formed
  int n_rings = 1;                    // ArapN
  double smooth_alpha = 0.0;          // > 0: sr-arap rotation smoothing (alpha)
  double bending_lambda = 0.0;        // > 0: arap-h / arap-sr-h bending (lambda / mean vertex area)
  // Bending rotations: true (arap-h) = one extra cluster per bending vertex with its own rotation; false
  // (arap-sr-h) = the bending term joins vertex i's own cluster (per-vertex structures only).
  bool bending_own_rotation = false;
};

struct EnergyModel {
  int vertex_count = 0;
  int cluster_count = 0;
  std::vector<int> cluster_start;  // cluster_count + 1; terms of c are [cluster_start[c], cluster_start[c+1])
  std::vector<int> term_vertex;    // local vertex of each term
  std::vector<int> term_cluster;   // cluster of each term
  Eigen::Matrix3Xd term_g;         // 3 by #terms, current weights
  Eigen::SparseMatrix<double> Q;   // n by n, both triangles stored, current weights
  double constant = 0.0;           // C, current weights

  // Rotation smoothing (sr-arap): neighbours of cluster c are smooth_cluster[smooth_start[c] .. [c+1]).
  // Clusters [rank_one_begin, cluster_count) (arap-h bending) have covariances u h_c^T with a known unit
  // h_c = rank_one_axis.col(c - rank_one_begin): their optimal rotation is any one turning h_c onto u.
  int rank_one_begin = 0;
  Eigen::Matrix3Xd rank_one_axis;

  double smooth_scale = 0.0;
  std::vector<int> smooth_start, smooth_cluster;
  std::vector<double> smooth_weight;

  // Refill term_g, Q values and constant from new slot weights (3 * #faces half cotangents).
  void set_weights(const Eigen::VectorXd& half_cot);

  // Construction data for set_weights.
  std::vector<int> entry_term_i, entry_term_j, entry_slot;
  Eigen::Matrix3Xd entry_e;
  Eigen::Matrix3Xd static_term_g;
  std::vector<int> q_value, q_slot;
  std::vector<double> q_coeff;
  std::vector<double> slot_multiplicity;
  Eigen::Matrix3Xd slot_e;  // rest edge vector of each slot
  Eigen::VectorXd static_q;
  double static_constant = 0.0;
};

// P: 3 by n rest positions; faces: local triangles (no repeated index); half_cot: initial weights (the
// clusters' weights; the smoothing and bending terms always use `rest_half_cot`, the real mesh's);
// bending_vertex: n flags, vertices whose one-ring is complete (arap-h).
[[nodiscard]] EnergyModel build_energy_model(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces,
                                             const ModelSpec& spec, const Eigen::VectorXd& half_cot,
                                             const Eigen::VectorXd& rest_half_cot,
                                             const std::vector<char>& bending_vertex);

}  // namespace pushpull::deform::detail
