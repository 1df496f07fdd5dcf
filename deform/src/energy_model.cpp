// Cluster builders for arap-s / arap-sr / arap-m / arap-n, plus the sr-arap and arap-h extra terms.
#include "energy_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <stdexcept>
#include <tuple>

namespace pushpull::deform::detail {
namespace {

using Triplet = Eigen::Triplet<double>;

// Index of entry (row, col) in Q's value array (the entry must exist).
int value_index(const Eigen::SparseMatrix<double>& Q, int row, int col) {
  const int* inner = Q.innerIndexPtr();
  const int begin = Q.outerIndexPtr()[col], end = Q.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  if (it == inner + end || *it != row) throw std::logic_error("energy model: missing matrix entry");
  return static_cast<int>(it - inner);
}

struct ClusterBuilder {
  const Eigen::Matrix3Xd& P;
  EnergyModel& m;
  std::vector<int> stamp;    // per vertex: last cluster that gave it a term
  std::vector<int> term_of;  // per vertex: its term in that cluster

  int term(int cluster, int v) {
    if (stamp[static_cast<std::size_t>(v)] != cluster) {
      stamp[static_cast<std::size_t>(v)] = cluster;
      term_of[static_cast<std::size_t>(v)] = static_cast<int>(m.term_vertex.size());
      m.term_vertex.push_back(v);
      m.term_cluster.push_back(cluster);
    }
    return term_of[static_cast<std::size_t>(v)];
  }
  // Weighted edge (i -> j) with the weight of `slot` in `cluster`.
  void edge(int cluster, int i, int j, int slot, std::vector<Eigen::Vector3d>& es) {
    m.entry_term_i.push_back(term(cluster, i));
    m.entry_term_j.push_back(term(cluster, j));
    m.entry_slot.push_back(slot);
    es.push_back(P.col(i) - P.col(j));
    m.slot_multiplicity[static_cast<std::size_t>(slot)] += 1.0;
  }
  void face_edges(int cluster, const Eigen::MatrixX3i& faces, int f, std::vector<Eigen::Vector3d>& es) {
    for (int k = 0; k < 3; ++k) edge(cluster, faces(f, (k + 1) % 3), faces(f, (k + 2) % 3), 3 * f + k, es);
  }
};

}  // namespace

void EnergyModel::set_weights(const Eigen::VectorXd& half_cot) {
  term_g = static_term_g;
  for (std::size_t e = 0; e < entry_slot.size(); ++e) {
    const Eigen::Vector3d we = half_cot(entry_slot[e]) * entry_e.col(static_cast<Eigen::Index>(e));
    term_g.col(entry_term_i[e]) += we;
    term_g.col(entry_term_j[e]) -= we;
  }
  Eigen::Map<Eigen::VectorXd>(Q.valuePtr(), Q.nonZeros()) = static_q;
  double* values = Q.valuePtr();
  for (std::size_t k = 0; k < q_value.size(); ++k) values[q_value[k]] += q_coeff[k] * half_cot(q_slot[k]);
  constant = static_constant;
  for (Eigen::Index s = 0; s < half_cot.size(); ++s) {
    constant += slot_multiplicity[static_cast<std::size_t>(s)] * half_cot(s) * slot_e.col(s).squaredNorm();
  }
}

EnergyModel build_energy_model(const Eigen::Matrix3Xd& P, const Eigen::MatrixX3i& faces,
                               const ModelSpec& spec, const Eigen::VectorXd& half_cot,
                               const Eigen::VectorXd& rest_half_cot,
                               const std::vector<char>& bending_vertex) {
  const int n = static_cast<int>(P.cols());
  const int nf = static_cast<int>(faces.rows());
  EnergyModel m;
  m.vertex_count = n;
  m.slot_multiplicity.assign(static_cast<std::size_t>(3 * nf), 0.0);
  m.slot_e.resize(3, 3 * nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k)
      m.slot_e.col(3 * f + k) = P.col(faces(f, (k + 1) % 3)) - P.col(faces(f, (k + 2) % 3));
  }

  // Vertex -> incident faces, and vertex adjacency (for n-rings and smoothing).
  std::vector<std::vector<int>> vertex_faces(static_cast<std::size_t>(n));
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      vertex_faces[static_cast<std::size_t>(faces(f, k))].push_back(f);
      neighbours[static_cast<std::size_t>(faces(f, k))].push_back(faces(f, (k + 1) % 3));
      neighbours[static_cast<std::size_t>(faces(f, k))].push_back(faces(f, (k + 2) % 3));
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }

  ClusterBuilder b{P, m, std::vector<int>(static_cast<std::size_t>(n), -1),
                   std::vector<int>(static_cast<std::size_t>(n), 0)};
  std::vector<Eigen::Vector3d> es;
  m.cluster_start.push_back(0);
  if (spec.structure == Method::ArapM) {
    for (int f = 0; f < nf; ++f) {
      b.face_edges(f, faces, f, es);
      m.cluster_start.push_back(static_cast<int>(m.term_vertex.size()));
    }
  } else {
    std::vector<int> face_stamp(static_cast<std::size_t>(nf), -1),
        ring_stamp(static_cast<std::size_t>(n), -1);
    for (int k = 0; k < n; ++k) {
      const auto& star = vertex_faces[static_cast<std::size_t>(k)];
      if (spec.structure == Method::ArapS) {
        for (int f : star) {
          int corner = 0;
          while (faces(f, corner) != k) ++corner;
          // Spokes (k, next) and (k, prev), weighted by the angle opposite each in this face.
          b.edge(k, k, faces(f, (corner + 1) % 3), 3 * f + (corner + 2) % 3, es);
          b.edge(k, k, faces(f, (corner + 2) % 3), 3 * f + (corner + 1) % 3, es);
        }
      } else if (spec.structure == Method::ArapSR || spec.n_rings <= 1) {
        for (int f : star) b.face_edges(k, faces, f, es);
      } else if (spec.structure == Method::ArapN) {
        // Faces incident to any vertex within n-1 rings of k.
        std::vector<int> ring = {k};
        ring_stamp[static_cast<std::size_t>(k)] = k;
        for (std::size_t s = 0, depth = 0; depth + 1 < static_cast<std::size_t>(spec.n_rings); ++depth) {
          const std::size_t e = ring.size();
          for (; s < e; ++s) {
            for (int nb : neighbours[static_cast<std::size_t>(ring[s])]) {
              if (ring_stamp[static_cast<std::size_t>(nb)] == k) continue;
              ring_stamp[static_cast<std::size_t>(nb)] = k;
              ring.push_back(nb);
            }
          }
        }
        for (int v : ring) {
          for (int f : vertex_faces[static_cast<std::size_t>(v)]) {
            if (face_stamp[static_cast<std::size_t>(f)] == k) continue;
            face_stamp[static_cast<std::size_t>(f)] = k;
            b.face_edges(k, faces, f, es);
          }
        }
      } else {
        throw std::logic_error("energy model: unsupported cluster structure");
      }
      m.cluster_start.push_back(static_cast<int>(m.term_vertex.size()));
    }
  }
  m.cluster_count = static_cast<int>(m.cluster_start.size()) - 1;
  m.entry_e.resize(3, static_cast<Eigen::Index>(es.size()));
  for (std::size_t e = 0; e < es.size(); ++e) m.entry_e.col(static_cast<Eigen::Index>(e)) = es[e];
  m.static_term_g = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(m.term_vertex.size()));

  // Edge weights of the real mesh: w_ij = sum of the half cotangents opposite (i, j).
  std::vector<std::tuple<int, int, double>> edge_w;
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = faces(f, (k + 1) % 3), j = faces(f, (k + 2) % 3);
      edge_w.emplace_back(std::min(i, j), std::max(i, j), rest_half_cot(3 * f + k));
    }
  }
  std::sort(edge_w.begin(), edge_w.end());
  std::vector<std::tuple<int, int, double>> edges;  // merged
  for (const auto& [i, j, w] : edge_w) {
    if (!edges.empty() && std::get<0>(edges.back()) == i && std::get<1>(edges.back()) == j) {
      std::get<2>(edges.back()) += w;
    } else {
      edges.emplace_back(i, j, w);
    }
  }

  std::vector<Triplet> triplets;
  for (int s = 0; s < 3 * nf; ++s) {
    if (m.slot_multiplicity[static_cast<std::size_t>(s)] == 0.0) continue;
    const int f = s / 3, k = s % 3;
    const int i = faces(f, (k + 1) % 3), j = faces(f, (k + 2) % 3);
    triplets.insert(triplets.end(), {Triplet(i, i, 0), Triplet(j, j, 0), Triplet(i, j, 0), Triplet(j, i, 0)});
  }

  m.rank_one_begin = m.cluster_count;
  // Bending (arap-h, arap-sr-h): lambda B^T M^-1 B with B the rows of the cotangent Laplacian at complete
  // vertices; the coupling -2 lambda R_i : (L X)_i H_i^T goes to vertex i's arap-sr cluster (arap-sr-h) or
  // to a new cluster of its own (arap-h).
  Eigen::SparseMatrix<double> bending_q;
  if (spec.bending_lambda > 0.0) {
    std::vector<Triplet> lt;
    for (const auto& [i, j, w] : edges) {
      lt.insert(lt.end(), {Triplet(i, j, -w), Triplet(j, i, -w), Triplet(i, i, w), Triplet(j, j, w)});
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> L(n, n);
    L.setFromTriplets(lt.begin(), lt.end());
    Eigen::VectorXd area = Eigen::VectorXd::Zero(n);
    for (int f = 0; f < nf; ++f) {
      const double a =
          0.5 *
          (P.col(faces(f, 1)) - P.col(faces(f, 0))).cross(P.col(faces(f, 2)) - P.col(faces(f, 0))).norm();
      for (int k = 0; k < 3; ++k) area(faces(f, k)) += a / 3.0;
    }
    std::vector<int> rows;
    double mean_area = 0.0;
    for (int i = 0; i < n; ++i) {
      if (bending_vertex[static_cast<std::size_t>(i)] && area(i) > 0.0)
        rows.push_back(i), mean_area += area(i);
    }
    if (!rows.empty()) {
      mean_area /= static_cast<double>(rows.size());
      const double lambda = spec.bending_lambda * mean_area;
      const Eigen::Matrix3Xd LP = (L * P.transpose()).transpose();  // 3 by n
      std::vector<Triplet> bt;
      std::vector<Eigen::Vector3d> axes;
      for (std::size_t r = 0; r < rows.size(); ++r) {
        const int i = rows[r];
        const Eigen::Vector3d H = LP.col(i) / area(i);
        m.static_constant += lambda * area(i) * H.squaredNorm();
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, i); it; ++it)
          bt.emplace_back(static_cast<int>(r), static_cast<int>(it.col()), it.value() / std::sqrt(area(i)));
        if (spec.bending_own_rotation) {
          // H = 0 (flat at rest): the term lambda A_i |H'_i|^2 has no rotation and lives in Q alone.
          if (!(H.squaredNorm() > 0.0)) continue;
          const int cluster = m.cluster_count++;
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, i); it; ++it)
            b.term(cluster, static_cast<int>(it.col()));
          m.cluster_start.push_back(static_cast<int>(m.term_vertex.size()));
          const Eigen::Index old_terms = m.static_term_g.cols();
          m.static_term_g.conservativeResize(3, static_cast<Eigen::Index>(m.term_vertex.size()));
          m.static_term_g.rightCols(m.static_term_g.cols() - old_terms).setZero();
          int t = m.cluster_start[static_cast<std::size_t>(cluster)];
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, i); it; ++it, ++t)
            m.static_term_g.col(t) += lambda * it.value() * H;
          axes.push_back(H.normalized());
          continue;
        }
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(L, i); it; ++it) {
          // The term (cluster i, vertex j) exists: cluster i holds i's one-ring (arap-sr structure).
          int t = m.cluster_start[static_cast<std::size_t>(i)];
          while (t < m.cluster_start[static_cast<std::size_t>(i) + 1] &&
                 m.term_vertex[static_cast<std::size_t>(t)] != it.col())
            ++t;
          if (t == m.cluster_start[static_cast<std::size_t>(i) + 1])
            throw std::logic_error("arap-h: missing term");
          m.static_term_g.col(t) += lambda * it.value() * H;
        }
      }
      m.rank_one_axis.resize(3, static_cast<Eigen::Index>(axes.size()));
      for (std::size_t k = 0; k < axes.size(); ++k)
        m.rank_one_axis.col(static_cast<Eigen::Index>(k)) = axes[k];
      Eigen::SparseMatrix<double> Bs(static_cast<Eigen::Index>(rows.size()), n);  // M^-1/2 B
      Bs.setFromTriplets(bt.begin(), bt.end());
      bending_q = lambda * Eigen::SparseMatrix<double>(Bs.transpose() * Bs);
      for (int c = 0; c < bending_q.outerSize(); ++c) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(bending_q, c); it; ++it) {
          triplets.emplace_back(static_cast<int>(it.row()), c, 0.0);
        }
      }
    }
  }

  m.Q.resize(n, n);
  m.Q.setFromTriplets(triplets.begin(), triplets.end());
  m.Q.makeCompressed();
  m.static_q = Eigen::VectorXd::Zero(m.Q.nonZeros());
  for (int c = 0; c < bending_q.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(bending_q, c); it; ++it) {
      m.static_q(value_index(m.Q, static_cast<int>(it.row()), c)) += it.value();
    }
  }
  for (int s = 0; s < 3 * nf; ++s) {
    const double mult = m.slot_multiplicity[static_cast<std::size_t>(s)];
    if (mult == 0.0) continue;
    const int f = s / 3, k = s % 3;
    const int i = faces(f, (k + 1) % 3), j = faces(f, (k + 2) % 3);
    for (const auto& [r, c, sign] :
         {std::tuple{i, i, 1.0}, std::tuple{j, j, 1.0}, std::tuple{i, j, -1.0}, std::tuple{j, i, -1.0}}) {
      m.q_value.push_back(value_index(m.Q, r, c));
      m.q_slot.push_back(s);
      m.q_coeff.push_back(sign * mult);
    }
  }

  // sr-arap: rotation smoothing over mesh edges, |w_kl| of the real mesh (per-vertex clusters only).
  if (spec.smooth_alpha > 0.0 && spec.structure != Method::ArapM) {
    double total_area = 0.0;
    for (int f = 0; f < nf; ++f) {
      total_area +=
          0.5 *
          (P.col(faces(f, 1)) - P.col(faces(f, 0))).cross(P.col(faces(f, 2)) - P.col(faces(f, 0))).norm();
    }
    m.smooth_scale = spec.smooth_alpha * total_area;
    std::vector<std::vector<std::pair<int, double>>> adj(static_cast<std::size_t>(n));
    for (const auto& [i, j, w] : edges) {
      adj[static_cast<std::size_t>(i)].emplace_back(j, std::abs(w));
      adj[static_cast<std::size_t>(j)].emplace_back(i, std::abs(w));
    }
    m.smooth_start.push_back(0);
    for (const auto& list : adj) {
      for (const auto& [c, w] : list) m.smooth_cluster.push_back(c), m.smooth_weight.push_back(w);
      m.smooth_start.push_back(static_cast<int>(m.smooth_cluster.size()));
    }
  }

  m.set_weights(half_cot);
  return m;
}

}  // namespace pushpull::deform::detail
