// Discrete Gaussian curvature: angle defect over mixed Voronoi area (Meyer et al. 2003).
#include "edge_key.hpp"
#include "pushpull/deform/metrics.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pushpull::deform {

namespace {

using detail::edge_key;

// Vertices on an edge of exactly one face (boundary), and on an edge of three or more (non-manifold).
void mark_edge_vertices(const Eigen::MatrixXi& F, Eigen::Index vertex_count, std::vector<bool>* boundary,
                        std::vector<bool>* non_manifold) {
  std::vector<std::uint64_t> edges;
  edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c);
      const int b = F(f, (c + 1) % 3);
      if (a != b) edges.push_back(edge_key(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  boundary->assign(static_cast<std::size_t>(vertex_count), false);
  non_manifold->assign(static_cast<std::size_t>(vertex_count), false);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) {
      std::vector<bool>& marked = j - i == 1 ? *boundary : *non_manifold;
      marked[static_cast<std::size_t>(edges[i] >> 32)] = true;
      marked[static_cast<std::size_t>(edges[i] & 0xffffffffu)] = true;
    }
    i = j;
  }
}

}  // namespace

GaussianCurvature gaussian_curvature(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("gaussian_curvature: V and F must have 3 columns");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())) {
    throw std::invalid_argument("gaussian_curvature: a face index is outside [0, " +
                                std::to_string(V.rows()) + ")");
  }
  const Eigen::Index n = V.rows();
  GaussianCurvature result;
  mark_edge_vertices(F, n, &result.boundary, &result.non_manifold);
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(n);
  result.area = Eigen::VectorXd::Zero(n);

  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int idx[3] = {F(f, 0), F(f, 1), F(f, 2)};
    const Eigen::Vector3d p[3] = {V.row(idx[0]).transpose(), V.row(idx[1]).transpose(),
                                  V.row(idx[2]).transpose()};
    const double double_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(double_area > 0.0)) continue;  // repeated vertex or collinear: no angles, no area
    double angle[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = p[(c + 1) % 3] - p[c];
      const Eigen::Vector3d v = p[(c + 2) % 3] - p[c];
      angle[c] = std::atan2(u.cross(v).norm(), u.dot(v));
    }
    const double area = 0.5 * double_area;
    const int obtuse = angle[0] > std::numbers::pi / 2   ? 0
                       : angle[1] > std::numbers::pi / 2 ? 1
                       : angle[2] > std::numbers::pi / 2 ? 2
                                                         : -1;
    for (int c = 0; c < 3; ++c) {
      angle_sum(idx[c]) += angle[c];
      if (obtuse < 0) {
        // Voronoi share: (|e_c,c+1|^2 cot(angle at c+2) + |e_c,c+2|^2 cot(angle at c+1)) / 8.
        const int c1 = (c + 1) % 3;
        const int c2 = (c + 2) % 3;
        const double cot1 = 1.0 / std::tan(angle[c1]);
        const double cot2 = 1.0 / std::tan(angle[c2]);
        result.area(idx[c]) +=
            ((p[c1] - p[c]).squaredNorm() * cot2 + (p[c2] - p[c]).squaredNorm() * cot1) / 8.0;
      } else {
        result.area(idx[c]) += obtuse == c ? area / 2.0 : area / 4.0;
      }
    }
  }

  result.angle_defect.resize(n);
  result.K.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double full =
        result.boundary[static_cast<std::size_t>(i)] ? std::numbers::pi : 2.0 * std::numbers::pi;
    result.angle_defect(i) = result.area(i) > 0.0 ? full - angle_sum(i) : 0.0;
    result.K(i) = result.area(i) > 0.0 ? result.angle_defect(i) / result.area(i) : 0.0;
  }
  return result;
}

double curvature_reference_length(const Eigen::MatrixXd& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

double flat_curvature_threshold(double reference_length, double flat_band) {
  if (!(reference_length > 0.0)) return 0.0;
  return flat_band / (reference_length * reference_length);
}

std::vector<std::int8_t> curvature_signs(const GaussianCurvature& curvature, double threshold) {
  std::vector<std::int8_t> signs(static_cast<std::size_t>(curvature.K.size()), 0);
  for (Eigen::Index i = 0; i < curvature.K.size(); ++i) {
    const double k = curvature.K(i);
    if (std::abs(k) <= threshold || std::abs(curvature.angle_defect(i)) <= kFlatAngleDefect) continue;
    signs[static_cast<std::size_t>(i)] = k > 0.0 ? 1 : -1;
  }
  return signs;
}

}  // namespace pushpull::deform
