// Displacement decomposition along d, norms over a vertex set, and the combined evaluation.
#include "pushpull/deform/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pushpull::deform {

namespace {

Eigen::Vector3d unit_direction(const Eigen::Vector3d& d) {
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw std::invalid_argument("displacement direction d must be non-zero and finite");
  }
  return d / length;
}

template <typename Magnitude>
NormSummary summarize(Eigen::Index count, std::span<const int> vertices, Magnitude magnitude) {
  NormSummary summary;
  double sum_squares = 0.0;
  std::size_t n = 0;
  auto add = [&](Eigen::Index i) {
    if (i < 0 || i >= count)
      throw std::invalid_argument("vertex index " + std::to_string(i) + " out of range");
    const double m = magnitude(i);
    sum_squares += m * m;
    summary.max = std::max(summary.max, m);
    ++n;
  };
  if (vertices.empty()) {
    for (Eigen::Index i = 0; i < count; ++i) add(i);
  } else {
    for (const int i : vertices) add(i);
  }
  summary.l2 = std::sqrt(sum_squares);
  summary.rms = n > 0 ? std::sqrt(sum_squares / static_cast<double>(n)) : 0.0;
  return summary;
}

}  // namespace

DisplacementDecomposition decompose_displacement(const Eigen::MatrixXd& V_before,
                                                 const Eigen::MatrixXd& V_after, const Eigen::Vector3d& d) {
  if (V_before.rows() != V_after.rows() || V_before.cols() != 3 || V_after.cols() != 3) {
    throw std::invalid_argument("decompose_displacement: V_before and V_after must both be #V by 3");
  }
  const Eigen::Vector3d unit = unit_direction(d);
  const Eigen::MatrixXd u = V_after - V_before;
  DisplacementDecomposition result;
  result.magnitude = u.rowwise().norm();
  result.along = u * unit;
  result.orthogonal = u - result.along * unit.transpose();
  return result;
}

NormSummary norms_over(const Eigen::VectorXd& values, std::span<const int> vertices) {
  return summarize(values.size(), vertices, [&](Eigen::Index i) { return std::abs(values(i)); });
}

NormSummary row_norms_over(const Eigen::MatrixXd& rows, std::span<const int> vertices) {
  return summarize(rows.rows(), vertices, [&](Eigen::Index i) { return rows.row(i).norm(); });
}

DeformationMetrics evaluate_deformation(const Mesh& before, const Eigen::MatrixXd& V_after,
                                        const Eigen::Vector3d& d, std::span<const int> vertices,
                                        const MetricsOptions& options) {
  const DisplacementDecomposition parts = decompose_displacement(before.V, V_after, d);
  std::vector<int> all;
  if (vertices.empty()) {
    all.resize(static_cast<std::size_t>(before.V.rows()));
    std::iota(all.begin(), all.end(), 0);
    vertices = all;
  }
  DeformationMetrics metrics;
  metrics.evaluated_vertices = vertices.size();
  metrics.displacement = norms_over(parts.magnitude, vertices);
  metrics.along_d = norms_over(parts.along, vertices);
  metrics.orthogonal = row_norms_over(parts.orthogonal, vertices);
  double along_sum = 0.0;
  for (const int i : vertices) along_sum += parts.along(i);
  metrics.mean_along_d = vertices.empty() ? 0.0 : along_sum / static_cast<double>(vertices.size());

  const GaussianCurvature k_before = gaussian_curvature(before.V, before.F);
  const GaussianCurvature k_after = gaussian_curvature(V_after, before.F);
  metrics.reference_length = curvature_reference_length(before.V);
  metrics.curvature_threshold = flat_curvature_threshold(metrics.reference_length, options.flat_band);
  const std::vector<std::int8_t> sign_before = curvature_signs(k_before, metrics.curvature_threshold);
  const std::vector<std::int8_t> sign_after = curvature_signs(k_after, metrics.curvature_threshold);
  for (const int i : vertices) {
    const auto v = static_cast<std::size_t>(i);
    if (!k_before.defined_at(v)) continue;
    ++metrics.curvature_vertices;
    metrics.positive_before += sign_before[v] > 0;
    metrics.negative_before += sign_before[v] < 0;
    metrics.positive_after += sign_after[v] > 0;
    metrics.negative_after += sign_after[v] < 0;
    metrics.sign_flips += sign_before[v] != sign_after[v];
    metrics.sign_reversals += sign_before[v] * sign_after[v] < 0;
    metrics.into_flat += sign_before[v] != 0 && sign_after[v] == 0;
    metrics.out_of_flat += sign_before[v] == 0 && sign_after[v] != 0;
  }
  for (const double band : options.reversal_bands) {
    if (!(band > 0.0) || !std::isfinite(band))
      throw std::invalid_argument("evaluate_deformation: a reversal band must be positive and finite, got " +
                                  std::to_string(band));
    BandReversals counted;
    counted.band = band;
    counted.radius_below = metrics.reference_length / std::sqrt(band);
    const double threshold = flat_curvature_threshold(metrics.reference_length, band);
    const std::vector<std::int8_t> before_signs = curvature_signs(k_before, threshold);
    for (const int i : vertices) {
      const auto v = static_cast<std::size_t>(i);
      if (!k_before.defined_at(v) || before_signs[v] == 0) continue;
      ++counted.compared;
      counted.reversals += before_signs[v] * sign_after[v] < 0;  // after: the sign rule's own band
    }
    metrics.reversals_by_band.push_back(counted);
  }
  if (metrics.curvature_vertices > 0) {
    const auto n = static_cast<double>(metrics.curvature_vertices);
    metrics.sign_flip_fraction = static_cast<double>(metrics.sign_flips) / n;
    metrics.sign_reversal_fraction = static_cast<double>(metrics.sign_reversals) / n;
  }

  const Eigen::Vector3d unit = d.normalized();
  for (const double offset : options.section_offsets) {
    Section section;
    section.offset = offset;
    const Eigen::Vector3d origin = options.section_origin + offset * unit;
    CarriedSection cut = plane_section_carried(before.V, V_after, before.F, origin, unit);
    section.before = std::move(cut.cut);
    section.carried = std::move(cut.carried);
    section.after = plane_section(V_after, before.F, origin, unit);
    metrics.sections.push_back(std::move(section));
  }
  return metrics;
}

}  // namespace pushpull::deform
