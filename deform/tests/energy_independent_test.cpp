// Every energy checked against an independent implementation of its formula (the formulas of
// deformer.hpp, written out here from the papers without the solver's cluster machinery): on a small
// irregular mesh with random deformed positions, the energy (rotations by SVD) must equal
// Deformer::energy, its finite-difference gradient must equal the analytic one, and one solver iteration
// (local step, then global step) must land where the test's own dense minimisation of E(., R) lands.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "pushpull/deform/deformer.hpp"
#include "pushpull/deform/roi.hpp"
#include "test_shapes.hpp"

namespace pushpull::deform {
namespace {

// One squared edge term w |(x_i - x_j) - R_c e|^2 of cluster c.
struct Term {
  int cluster, i, j;
  double w;
  Eigen::Vector3d e;
};

// One bending term (arap-h, arap-sr-h) of vertex i: (lambda / A_i) |sum_j L_ij x_j - R (L P)_i|^2, R the
// rotation of cluster `rotation` (arap-h: one of its own; arap-sr-h: vertex i's arap-sr cluster).
struct Bend {
  int i;
  int rotation;
  double scale;                             // lambda / A_i
  std::vector<std::pair<int, double>> row;  // (j, L_ij)
  Eigen::Vector3d LP;
};

struct Formula {
  int clusters = 0;
  std::vector<Term> terms;
  std::vector<Bend> bends;
  // sr-arap: alpha A sum over mesh edges (k, l) |w_kl| ||R_k - R_l||_F^2.
  double smooth = 0.0;
  std::vector<std::tuple<int, int, double>> smooth_edges;
};

Eigen::Matrix3d polar(const Eigen::Matrix3d& A) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
  return U * svd.matrixV().transpose();
}

// Half cotangent of the angle at corner k of triangle (a, b, c) of P (3 by n or #V by 3 rows).
double triangle_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int face) {
  const Eigen::Vector3d a = V.row(F(face, 0)), b = V.row(F(face, 1)), c = V.row(F(face, 2));
  return 0.5 * (b - a).cross(c - a).norm();
}

double half_cot(const Eigen::Vector3d& apex, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const Eigen::Vector3d a = u - apex, b = v - apex;
  return 0.5 * a.dot(b) / a.cross(b).norm();
}

// The rotations minimising E for positions X (#V by 3): SVD of each cluster's covariance; with smoothing,
// Gauss-Seidel sweeps from the uncoupled optimum.
std::vector<Eigen::Matrix3d> rotations(const Formula& f, const Eigen::MatrixXd& X, int sweeps = 60) {
  std::vector<Eigen::Matrix3d> S(static_cast<std::size_t>(f.clusters), Eigen::Matrix3d::Zero());
  for (const Term& t : f.terms)
    S[static_cast<std::size_t>(t.cluster)] += t.w * (X.row(t.i) - X.row(t.j)).transpose() * t.e.transpose();
  for (const Bend& b : f.bends) {
    Eigen::Vector3d LX = Eigen::Vector3d::Zero();
    for (const auto& [j, l] : b.row) LX += l * X.row(j).transpose();
    S[static_cast<std::size_t>(b.rotation)] += b.scale * LX * b.LP.transpose();
  }
  std::vector<Eigen::Matrix3d> R(S.size());
  for (std::size_t c = 0; c < S.size(); ++c) R[c] = polar(S[c]);
  if (f.smooth > 0.0) {
    std::vector<std::vector<std::pair<int, double>>> adj(S.size());
    for (const auto& [k, l, w] : f.smooth_edges) {
      adj[static_cast<std::size_t>(k)].emplace_back(l, w);
      adj[static_cast<std::size_t>(l)].emplace_back(k, w);
    }
    for (int s = 0; s < sweeps; ++s) {
      for (std::size_t c = 0; c < S.size(); ++c) {
        Eigen::Matrix3d A = S[c];
        for (const auto& [d, w] : adj[c]) A += f.smooth * w * R[static_cast<std::size_t>(d)];
        R[c] = polar(A);
      }
    }
  }
  return R;
}

double energy(const Formula& f, const Eigen::MatrixXd& X, const std::vector<Eigen::Matrix3d>& R) {
  double E = 0.0;
  for (const Term& t : f.terms)
    E += t.w *
         ((X.row(t.i) - X.row(t.j)).transpose() - R[static_cast<std::size_t>(t.cluster)] * t.e).squaredNorm();
  for (const Bend& b : f.bends) {
    Eigen::Vector3d LX = Eigen::Vector3d::Zero();
    for (const auto& [j, l] : b.row) LX += l * X.row(j).transpose();
    E += b.scale * (LX - R[static_cast<std::size_t>(b.rotation)] * b.LP).squaredNorm();
  }
  for (const auto& [k, l, w] : f.smooth_edges)
    E += f.smooth * w * (R[static_cast<std::size_t>(k)] - R[static_cast<std::size_t>(l)]).squaredNorm();
  return E;
}

// dE/dX at fixed R (= dE/dX of min_R E, by the envelope theorem), #V by 3.
Eigen::MatrixXd gradient(const Formula& f, const Eigen::MatrixXd& X, const std::vector<Eigen::Matrix3d>& R) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(X.rows(), 3);
  for (const Term& t : f.terms) {
    const Eigen::Vector3d r =
        2.0 * t.w * ((X.row(t.i) - X.row(t.j)).transpose() - R[static_cast<std::size_t>(t.cluster)] * t.e);
    G.row(t.i) += r.transpose();
    G.row(t.j) -= r.transpose();
  }
  for (const Bend& b : f.bends) {
    Eigen::Vector3d LX = Eigen::Vector3d::Zero();
    for (const auto& [j, l] : b.row) LX += l * X.row(j).transpose();
    const Eigen::Vector3d r = 2.0 * b.scale * (LX - R[static_cast<std::size_t>(b.rotation)] * b.LP);
    for (const auto& [j, l] : b.row) G.row(j) += l * r.transpose();
  }
  return G;
}

struct SmallProblem {
  std::shared_ptr<const Mesh> mesh;
  RegionOfInterest roi;
  Eigen::Vector3d d{0.03, -0.02, 0.08};
};

SmallProblem make_setup() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Mesh m = testing::grid(6, 6, 0.0, 1.0, 0.0, 1.0, [](double x, double y) { return 0.3 * x * y; });
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const bool border = m.V(v, 0) < 1e-9 || m.V(v, 0) > 1 - 1e-9 || m.V(v, 1) < 1e-9 || m.V(v, 1) > 1 - 1e-9;
    if (!border) m.V.row(v) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
  }
  SmallProblem s;
  s.mesh = std::make_shared<const Mesh>(m);
  std::vector<int> fixed;
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const int i = static_cast<int>(v % 7), j = static_cast<int>(v / 7);
    if (i == 0 || j == 0 || i == 6 || j == 6) fixed.push_back(static_cast<int>(v));
  }
  s.roi = make_roi(m, std::vector<int>{3 * 7 + 3, 3 * 7 + 4}, fixed, {});  // whole mesh, border fixed
  return s;
}

// The formula of `method` on mesh m (every face in the region), from deformer.hpp's definitions.
Formula formula(const Mesh& m, Method method, const DeformOptions& o, const Eigen::Vector3d& d) {
  Formula f;
  const int nv = static_cast<int>(m.V.rows()), nf = static_cast<int>(m.F.rows());
  // Weights: half cotangents of the real mesh, or of its stretched copy for asan.
  Eigen::MatrixXd P = m.V;
  if (method == Method::Asan) {
    const Eigen::Vector3d u = d.normalized();
    const Eigen::Matrix3d tau = Eigen::Matrix3d::Identity() + (o.mu - 1.0) * u * u.transpose();
    P = (tau * m.V.transpose()).transpose();
  }
  auto corner_weight = [&](const Eigen::MatrixXd& Q, int face,
                           int k) {  // half cot at corner k, edge opposite
    const int a = m.F(face, k), b = m.F(face, (k + 1) % 3), c = m.F(face, (k + 2) % 3);
    return half_cot(Q.row(a), Q.row(b), Q.row(c));
  };
  auto face_terms = [&](int cluster, int face) {
    for (int k = 0; k < 3; ++k) {
      const int i = m.F(face, (k + 1) % 3), j = m.F(face, (k + 2) % 3);
      f.terms.push_back({cluster, i, j, corner_weight(P, face, k), (m.V.row(i) - m.V.row(j)).transpose()});
    }
  };
  std::vector<std::set<int>> faces_of(static_cast<std::size_t>(nv)), ring(static_cast<std::size_t>(nv));
  std::map<std::pair<int, int>, double> spoke;  // (cot a + cot b) / 2 of the real mesh
  for (int face = 0; face < nf; ++face) {
    for (int k = 0; k < 3; ++k) {
      const int i = m.F(face, (k + 1) % 3), j = m.F(face, (k + 2) % 3);
      faces_of[static_cast<std::size_t>(m.F(face, k))].insert(face);
      ring[static_cast<std::size_t>(i)].insert(j);
      ring[static_cast<std::size_t>(j)].insert(i);
      spoke[{std::min(i, j), std::max(i, j)}] += corner_weight(m.V, face, k);
    }
  }
  const Method structure = method == Method::Asan                                    ? o.asan_base
                           : (method == Method::SrArap || method == Method::ArapSrH) ? Method::ArapSR
                           : method == Method::ArapH                                 ? Method::ArapM
                                                                                     : method;
  switch (structure) {
    case Method::ArapS: {  // cluster k: its spokes, both directions
      f.clusters = nv;
      for (const auto& [edge, w] : spoke) {
        const auto [i, j] = edge;
        f.terms.push_back({i, i, j, w, (m.V.row(i) - m.V.row(j)).transpose()});
        f.terms.push_back({j, j, i, w, (m.V.row(j) - m.V.row(i)).transpose()});
      }
      break;
    }
    case Method::ArapM:  // cluster t: its three edges
      f.clusters = nf;
      for (int face = 0; face < nf; ++face) face_terms(face, face);
      break;
    case Method::ArapN: {  // cluster k: the faces touching a vertex at most n-1 rings from k
      f.clusters = nv;
      for (int k = 0; k < nv; ++k) {
        std::set<int> near{k};
        for (int r = 1; r < o.arap_n_rings; ++r) {
          std::set<int> next = near;
          for (int v : near)
            next.insert(ring[static_cast<std::size_t>(v)].begin(), ring[static_cast<std::size_t>(v)].end());
          near = next;
        }
        std::set<int> faces;
        for (int v : near)
          faces.insert(faces_of[static_cast<std::size_t>(v)].begin(),
                       faces_of[static_cast<std::size_t>(v)].end());
        for (int face : faces) face_terms(k, face);
      }
      break;
    }
    default:  // arap-sr: cluster k: the edges of the faces around k
      f.clusters = nv;
      for (int k = 0; k < nv; ++k)
        for (int face : faces_of[static_cast<std::size_t>(k)]) face_terms(k, face);
      break;
  }
  if (method == Method::SrArap) {
    double area = 0.0;
    for (int face = 0; face < nf; ++face) area += triangle_area(m.V, m.F, face);
    f.smooth = o.sr_arap_alpha * area;
    for (const auto& [edge, w] : spoke) f.smooth_edges.emplace_back(edge.first, edge.second, std::abs(w));
  }
  if (method == Method::ArapH || method == Method::ArapSrH) {
    // H = M^-1 L p at interior vertices (complete one-ring), A_i = a third of the incident faces' area,
    // lambda = arap_h_lambda * mean A_i over those vertices. arap-h: a rotation per interior vertex, after
    // the triangles' ones; arap-sr-h: the vertex's own arap-sr rotation.
    Eigen::VectorXd A = Eigen::VectorXd::Zero(nv);
    for (int face = 0; face < nf; ++face) {
      const double a = triangle_area(m.V, m.F, face);
      for (int k = 0; k < 3; ++k) A(m.F(face, k)) += a / 3.0;
    }
    std::vector<int> interior;
    for (int v = 0; v < nv; ++v) {
      const int i = v % 7, j = v / 7;
      if (i > 0 && j > 0 && i < 6 && j < 6) interior.push_back(v);
    }
    double mean = 0.0;
    for (int v : interior) mean += A(v);
    mean /= static_cast<double>(interior.size());
    const double lambda = o.arap_h_lambda * mean;
    for (int v : interior) {
      Bend b;
      b.i = v;
      b.rotation = method == Method::ArapH ? f.clusters++ : v;
      b.scale = lambda / A(v);
      double diagonal = 0.0;
      b.LP = Eigen::Vector3d::Zero();
      for (int j : ring[static_cast<std::size_t>(v)]) {
        const double w = spoke.at({std::min(v, j), std::max(v, j)});
        b.row.emplace_back(j, -w);
        diagonal += w;
        b.LP += w * (m.V.row(v) - m.V.row(j)).transpose();
      }
      b.row.emplace_back(v, diagonal);
      f.bends.push_back(b);
    }
  }
  return f;
}

class EnergyIndependent : public ::testing::TestWithParam<Method> {};

TEST_P(EnergyIndependent, EnergyGradientAndGlobalStepMatchTheFormula) {
  const SmallProblem s = make_setup();
  const Method method = GetParam();
  DeformOptions o;
  o.method = method;
  o.anderson_window = 0;
  o.tolerance = 0.0;
  o.max_iterations = 1;
  const Formula f = formula(*s.mesh, method, o, s.d);

  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  Eigen::MatrixXd X = s.mesh->V;
  for (Eigen::Index v = 0; v < X.rows(); ++v)
    X.row(v) += Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));
  for (int h : s.roi.handle) X.row(h) = s.mesh->V.row(h) + s.d.transpose();
  for (int v : s.roi.fixed) X.row(v) = s.mesh->V.row(v);

  Deformer deformer(s.mesh, s.roi, o);
  ConstraintTargets targets = deformer.push_pull_targets(s.d);
  targets.initial_guess = X;
  const DeformResult one = deformer.solve(targets);  // also sets asan's weights for d

  // 1. The energy, rotations by SVD.
  const std::vector<Eigen::Matrix3d> R = rotations(f, X);
  const double E = energy(f, X, R);
  EXPECT_NEAR(deformer.energy(X), E, (method == Method::SrArap ? 1e-6 : 1e-10) * E) << method_name(method);

  // 2. Its gradient by central differences (envelope theorem: rotations re-optimised at each sample).
  const Eigen::MatrixXd G = gradient(f, X, R);
  const double h = 1e-6;
  for (int v : s.roi.free) {
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd Xp = X, Xm = X;
      Xp(v, c) += h;
      Xm(v, c) -= h;
      const double fd = (energy(f, Xp, rotations(f, Xp)) - energy(f, Xm, rotations(f, Xm))) / (2 * h);
      EXPECT_NEAR(fd, G(v, c), 1e-6 * (1.0 + std::abs(G(v, c)))) << method_name(method) << " vertex " << v;
    }
  }

  // 3. One local-global iteration from X: the minimiser of E(., R(X)) over the free vertices, solved densely.
  if (method != Method::SrArap) {  // sr-arap's first local step is one Gauss-Seidel sweep, not the optimum
    const int nf = static_cast<int>(s.roi.free.size());
    std::map<int, int> index;
    for (int k = 0; k < nf; ++k) index[s.roi.free[static_cast<std::size_t>(k)]] = k;
    // E(Y) = sum |sum_k a_k y_k - r|^2 over linear residuals; normal equations H Y = B.
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(nf, nf), B = Eigen::MatrixXd::Zero(nf, 3);
    auto add = [&](const std::vector<std::pair<int, double>>& row, const Eigen::Vector3d& target, double w) {
      Eigen::Vector3d r = target;  // target minus the constrained part
      for (const auto& [v, a] : row)
        if (!index.count(v)) r -= a * X.row(v).transpose();
      for (const auto& [v, a] : row) {
        if (!index.count(v)) continue;
        B.row(index[v]) += w * a * r.transpose();
        for (const auto& [u, b] : row)
          if (index.count(u)) H(index[v], index[u]) += w * a * b;
      }
    };
    for (const Term& t : f.terms)
      add({{t.i, 1.0}, {t.j, -1.0}}, R[static_cast<std::size_t>(t.cluster)] * t.e, t.w);
    for (const Bend& b : f.bends) add(b.row, R[static_cast<std::size_t>(b.rotation)] * b.LP, b.scale);
    const Eigen::MatrixXd Y = H.ldlt().solve(B);
    double worst = 0.0;
    for (int k = 0; k < nf; ++k)
      worst = std::max(worst, (one.V.row(s.roi.free[static_cast<std::size_t>(k)]) - Y.row(k)).norm());
    EXPECT_LT(worst, 1e-9) << method_name(method);
  }
}

INSTANTIATE_TEST_SUITE_P(AllMethods, EnergyIndependent, ::testing::ValuesIn(kAllMethods),
                         [](const auto& info) {
                           std::string name(method_name(info.param));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The parameters change the energy they claim to change.
TEST(EnergyParameters, EachParameterMatters) {
  const SmallProblem s = make_setup();
  // Fresh option structs (no copies: GCC 12 warns about copying the optional stretch direction).
  auto solve = [&](Method method, int rings, double alpha, double lambda) {
    DeformOptions o;
    o.method = method;
    o.arap_n_rings = rings;
    o.sr_arap_alpha = alpha;
    o.arap_h_lambda = lambda;
    return Deformer(s.mesh, s.roi, o).solve(s.d).V;
  };
  const Eigen::MatrixXd sr = solve(Method::ArapSR, 2, 0.02, 1.0);
  EXPECT_GT((solve(Method::ArapN, 2, 0.02, 1.0) - sr).norm(), 1e-4);  // n = 2 is not arap-sr
  EXPECT_LT((solve(Method::ArapN, 1, 0.02, 1.0) - sr).norm(), 1e-9);  // n = 1 is
  EXPECT_GT((solve(Method::SrArap, 2, 0.5, 1.0) - solve(Method::SrArap, 2, 0.0, 1.0)).norm(), 1e-4);
  EXPECT_GT((solve(Method::ArapH, 2, 0.02, 5.0) - solve(Method::ArapH, 2, 0.02, 0.0)).norm(), 1e-4);
  EXPECT_LT((solve(Method::ArapH, 2, 0.02, 0.0) - solve(Method::ArapM, 2, 0.02, 1.0)).norm(), 1e-9);
  EXPECT_GT((solve(Method::ArapSrH, 2, 0.02, 5.0) - solve(Method::ArapSrH, 2, 0.02, 0.0)).norm(), 1e-4);
  EXPECT_LT((solve(Method::ArapSrH, 2, 0.02, 0.0) - sr).norm(), 1e-9);
  // The two bending variants are different energies (own rotations on arap-m vs borrowed arap-sr ones).
  EXPECT_GT((solve(Method::ArapH, 2, 0.02, 5.0) - solve(Method::ArapSrH, 2, 0.02, 5.0)).norm(), 1e-4);
}

}  // namespace
}  // namespace pushpull::deform
